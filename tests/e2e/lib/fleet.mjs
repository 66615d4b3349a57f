// The fleet's outside pieces for browser tests: a real mosquitto on a loopback port and
// `docent fleet --mqtt` serving the fleet view alone, each awaited by the line it prints when
// ready (a deadline, never a pause). Used by fleet.test.mjs and accessibility.test.mjs.

import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import { DEADLINE_MS, docentBin, freePort, OPERATOR_TOKEN } from './docent.mjs';

/** Resolves when `stream` prints a line matching `pattern` (its match), within the deadline. */
function awaitLine(child, stream, pattern, what) {
  return new Promise((resolve, reject) => {
    let seen = '';
    const timer = setTimeout(() => reject(new Error(`${what} within ${DEADLINE_MS} ms; saw:\n${seen}`)), DEADLINE_MS);
    child[stream].setEncoding('utf8');
    child[stream].on('data', (chunk) => {
      seen += chunk;
      const found = pattern.exec(seen);
      if (found) {
        clearTimeout(timer);
        resolve(found);
      }
    });
    child.once('exit', (code) => {
      clearTimeout(timer);
      reject(new Error(`${what}: exited (${code}):\n${seen}`));
    });
  });
}

/**
 * mosquitto on 127.0.0.1:`port`, once it listens: `mosquitto version X running` comes after it
 * has bound its listeners (its earlier `Opening ipv4 listen socket` line comes before the bind).
 */
export async function startMosquitto(port, dir) {
  const conf = path.join(dir, 'mosquitto.conf');
  fs.writeFileSync(conf, `listener ${port} 127.0.0.1\nallow_anonymous true\npersistence false\nlog_dest stderr\nlog_type all\n`);
  const binary = ['/usr/sbin/mosquitto', '/usr/bin/mosquitto'].find((p) => fs.existsSync(p));
  assert.ok(binary, 'mosquitto is installed (scripts/install-test-deps.sh)');
  const child = spawn(binary, ['-c', conf], { stdio: ['ignore', 'ignore', 'pipe'] });
  await awaitLine(child, 'stderr', /mosquitto version \S+ running/, 'mosquitto listens');
  return child;
}

/** `docent fleet --mqtt URL` on a free port; its base URL once it serves. */
export async function startFleet(url) {
  const port = await freePort();
  const child = spawn(docentBin(), ['fleet', '--mqtt', url, '--listen', `127.0.0.1:${port}`], {
    stdio: ['ignore', 'pipe', 'ignore'],
    env: { ...process.env, RUST_LOG: 'docent=warn', DOCENT_OPERATOR_TOKEN: OPERATOR_TOKEN },
  });
  const [, base] = await awaitLine(child, 'stdout', /fleet:\s+(http:\/\/\S+)\/fleet/, 'docent fleet prints its address');
  return { child, base };
}
