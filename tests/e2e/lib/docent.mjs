// The real `docent` binary as a child process, plus temporary bundles and the corpus log.
//
// `startDocent` runs `docent serve BUNDLE --listen 127.0.0.1:PORT --corpus TMP`, waits for the
// start-up lines it prints on stdout (the "websocket:" line gives the address) and keeps draining
// stdout and stderr so the server never blocks on a full pipe; the output is kept for failure
// messages. `stop()` sends SIGTERM and waits for the graceful exit, which flushes the corpus log.
// The binary is $DOCENT_BIN, or target/debug/docent in the repository (built by `cargo test`).

import { spawn } from 'node:child_process';
import fs from 'node:fs';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

/** The repository root. */
export const REPO = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../..');

/** The operator credential every test server gets (DOCENT_OPERATOR_TOKEN). */
export const OPERATOR_TOKEN = 'e2e-operator-credential';
/** The dialog-manager credential every test server gets (DOCENT_DM_TOKEN). */
export const DM_TOKEN = 'e2e-dialog-manager-credential';

/** How long one wait may take before a test fails: a deadline, never a pause. */
export const DEADLINE_MS = 20_000;

/** The docent binary the tests run. */
export function docentBin() {
  return process.env.DOCENT_BIN ? path.resolve(process.env.DOCENT_BIN) : path.join(REPO, 'target/debug/docent');
}

/** A new temporary folder, removed by `removeTemp`. */
export function tempDir(prefix = 'docent-e2e-') {
  return fs.mkdtempSync(path.join(os.tmpdir(), prefix));
}

/** Removes a folder made by `tempDir` (or a bundle copy). */
export function removeTemp(dir) {
  if (dir) fs.rmSync(dir, { recursive: true, force: true });
}

/**
 * Copies a shipped bundle (`dialogs/NAME`) into a temporary folder and writes `files` over it,
 * e.g. `{'docent.yaml': '...'}`. Returns the copy's path.
 */
export function copyBundle(name, files = {}) {
  const dir = tempDir(`docent-e2e-${path.basename(name)}-`);
  fs.cpSync(path.join(REPO, 'dialogs', name), dir, { recursive: true });
  writeFiles(dir, files);
  return dir;
}

/** A bundle made of `files` only (relative path to contents) in a temporary folder. */
export function makeBundle(files) {
  const dir = tempDir('docent-e2e-bundle-');
  fs.mkdirSync(path.join(dir, 'pages'));
  fs.mkdirSync(path.join(dir, 'media'));
  writeFiles(dir, files);
  return dir;
}

function writeFiles(dir, files) {
  for (const [rel, contents] of Object.entries(files)) {
    const file = path.join(dir, rel);
    fs.mkdirSync(path.dirname(file), { recursive: true });
    fs.writeFileSync(file, contents);
  }
}

/** A TCP port on 127.0.0.1 that was free a moment ago (bound to 0, then closed). */
export function freePort() {
  return new Promise((resolve, reject) => {
    const server = net.createServer();
    server.once('error', reject);
    server.listen(0, '127.0.0.1', () => {
      const { port } = server.address();
      server.close(() => resolve(port));
    });
  });
}

/**
 * Starts `docent serve` on `bundle` (a path). Options: `port` (default 0: any free port),
 * `corpus` (a folder; default a new temporary one), `args` (more command-line arguments),
 * `env` (more environment; the credentials default to OPERATOR_TOKEN and DM_TOKEN).
 */
/** One media cache for this test process, so the tests never write the user's own. */
let mediaCache = null;

export async function startDocent(bundle, { port = 0, corpus, args = [], env = {} } = {}) {
  const corpusDir = corpus ?? tempDir('docent-e2e-corpus-');
  mediaCache ??= tempDir('docent-e2e-media-');
  const bin = docentBin();
  if (!fs.existsSync(bin)) {
    throw new Error(`no docent binary at ${bin}: run \`cargo build\` first or set DOCENT_BIN`);
  }
  const child = spawn(
    bin,
    ['serve', bundle, '--listen', `127.0.0.1:${port}`, '--corpus', corpusDir, '--seed', '1', ...args],
    {
      stdio: ['ignore', 'pipe', 'pipe'],
      env: {
        ...process.env,
        RUST_LOG: process.env.RUST_LOG ?? 'docent=warn',
        XDG_CACHE_HOME: mediaCache,
        DOCENT_OPERATOR_TOKEN: OPERATOR_TOKEN,
        DOCENT_DM_TOKEN: DM_TOKEN,
        ...env,
      },
    },
  );
  let output = '';
  const outputWaiters = new Set();
  const keep = (chunk) => {
    output += chunk;
    if (output.length > 64_000) output = output.slice(-32_000);
    for (const waiter of outputWaiters) waiter();
  };
  child.stdout.setEncoding('utf8');
  child.stderr.setEncoding('utf8');
  child.stderr.on('data', keep);
  const exited = new Promise((resolve) => child.once('exit', (code, signal) => resolve({ code, signal })));

  const started = new Promise((resolve, reject) => {
    let stdout = '';
    const onData = (chunk) => {
      keep(chunk);
      stdout += chunk;
      const ws = /^\s*websocket:\s+(ws:\/\/\S+)$/m.exec(stdout);
      const corpusLog = /^\s*corpus:\s+(\S+)/m.exec(stdout);
      if (ws && corpusLog) {
        // Keep draining: the server must never block on a full stdout pipe.
        child.stdout.off('data', onData);
        child.stdout.on('data', keep);
        resolve({ wsUrl: ws[1], corpus: corpusLog[1] });
      }
    };
    child.stdout.on('data', onData);
    exited.then(({ code, signal }) =>
      reject(new Error(`docent exited (${code ?? signal}) before it was serving:\n${output}`)),
    );
  });
  const { wsUrl, corpus: corpusFolder } = await withDeadline(started, DEADLINE_MS, () => {
    child.kill('SIGKILL');
    return `docent did not print its addresses within ${DEADLINE_MS} ms:\n${output}`;
  });
  const base = wsUrl.replace(/^ws:/, 'http:').replace(/\/ws$/, '');

  let stopping = null;
  return {
    base,
    wsUrl,
    corpusDir,
    /** The corpus folder as Docent printed it (absolute). */
    corpus: corpusFolder,
    port: Number(new URL(base).port),
    process: child,
    output: () => output,
    /**
     * Resolves with the output once it matches `pattern` (stdout and stderr are separate pipes:
     * a line logged before the addresses may arrive after them).
     */
    waitForOutput: (pattern) =>
      withDeadline(
        new Promise((resolve) => {
          const check = () => {
            if (!pattern.test(output)) return;
            outputWaiters.delete(check);
            resolve(output);
          };
          outputWaiters.add(check);
          check();
        }),
        DEADLINE_MS,
        () => `docent's output never matched ${pattern}:\n${output}`,
      ),
    /**
     * GET or POST a JSON route with the operator credential, e.g. `api('/api/state')`,
     * `api('/api/acts/X/trigger', {})`.
     */
    async api(route, body) {
      const headers = { authorization: `Bearer ${OPERATOR_TOKEN}` };
      const init = body === undefined ? { headers } : { method: 'POST', headers, body: JSON.stringify(body) };
      const res = await fetch(base + route, init);
      const json = await res.json();
      if (!res.ok) throw new Error(`${route}: ${res.status} ${JSON.stringify(json)}`);
      return json;
    },
    /** Triggers an act over HTTP. */
    trigger(label, body = {}) {
      return this.api(`/api/acts/${encodeURIComponent(label)}/trigger`, body);
    },
    /** SIGTERM, then waits for the exit (SIGKILL after the deadline). Returns the exit status. */
    stop() {
      stopping ??= (async () => {
        if (child.exitCode === null && child.signalCode === null) child.kill('SIGTERM');
        return withDeadline(exited, DEADLINE_MS, () => {
          child.kill('SIGKILL');
          return `docent did not exit within ${DEADLINE_MS} ms of SIGTERM:\n${output}`;
        });
      })();
      return stopping;
    },
  };
}

/** The events of a corpus log file, in order (a torn last line of a killed run is skipped). */
/**
 * Every event of a corpus folder holding one run (its day logs and its sessions' logs, see
 * docs/CORPUS.md), in `seq` order. A last line cut short by a kill is skipped.
 */
export function corpusEvents(corpus) {
  const logs = [];
  const days = path.join(corpus, 'days');
  for (const day of listed(days)) {
    for (const log of listed(path.join(days, day))) if (log.endsWith('.jsonl')) logs.push(path.join(days, day, log));
  }
  const sessions = path.join(corpus, 'sessions');
  for (const session of listed(sessions)) logs.push(path.join(sessions, session, 'events.jsonl'));
  const events = [];
  for (const log of logs.filter((l) => fs.existsSync(l))) {
    const lines = fs.readFileSync(log, 'utf8').split('\n').filter(Boolean);
    for (const [i, line] of lines.entries()) {
      try {
        events.push(JSON.parse(line));
      } catch (e) {
        if (i !== lines.length - 1) throw e;
      }
    }
  }
  return events.sort((a, b) => a.seq - b.seq);
}

/** The names in `dir`, sorted; none when it does not exist. */
function listed(dir) {
  return fs.existsSync(dir) ? fs.readdirSync(dir).sort() : [];
}

/** Resolves like `promise`, or rejects with `message()` once `ms` have passed. */
export function withDeadline(promise, ms, message) {
  let timer;
  const deadline = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(typeof message === 'function' ? message() : message)), ms);
  });
  return Promise.race([promise, deadline]).finally(() => clearTimeout(timer));
}
