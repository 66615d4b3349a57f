// The corpus disk filling up under a running server, in headless Chromium: the real `docent`
// binary logs into a small tmpfs (mounted here: the tests run as root, and fail loudly if
// they cannot mount); the disk is filled and triggered on until the server refuses. The
// operator console shows the server's words at once ("The corpus disk is full (...): free
// space on it; triggers are refused until then."), so does a console opened later (from its
// welcome), and once the filler is removed it shows that the log is written again. Every wait
// is for an event or an element, with a deadline only.

import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, watchExceptions } from './lib/browser.mjs';
import { DEADLINE_MS, makeBundle, removeTemp, startDocent, tempDir } from './lib/docent.mjs';
import { newConsoleContext, signIn } from './lib/operator.mjs';
import { connectOperator } from './lib/ws-client.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/** Mounts a tmpfs of `kib` KiB on `dir`; as root only (never skipped). */
function mountTmpfs(dir, kib) {
  assert.equal(process.getuid(), 0, 'this test mounts a tmpfs and must run as root');
  execFileSync('mount', ['-t', 'tmpfs', '-o', `size=${kib}k`, 'tmpfs', dir]);
}

/** Writes `file` until the disk is full. */
function fill(file) {
  const fd = fs.openSync(file, 'w');
  const page = Buffer.alloc(4096);
  try {
    for (;;) fs.writeSync(fd, page);
  } catch (error) {
    assert.equal(error.code, 'ENOSPC', String(error));
  } finally {
    fs.closeSync(fd);
  }
}

test('the console says at once that the corpus disk is full, and when it is written again', { timeout: 60_000 }, async () => {
  const bundle = makeBundle({
    'acts.yaml': '- Label: OK\n  Cmds: [DISPLAY_PAGE index.html]\n',
    'pages/index.html': '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>home</title></head><body></body></html>\n',
  });
  const scratch = tempDir('docent-e2e-disk-');
  const corpus = path.join(scratch, 'corpus');
  fs.mkdirSync(corpus);
  mountTmpfs(corpus, 512);
  let server = null;
  let operator = null;
  const context = await newConsoleContext(browser);
  try {
    server = await startDocent(bundle, { corpus });
    operator = await connectOperator(server.wsUrl);
    const console = await context.newPage();
    const exceptions = watchExceptions(console);
    await signIn(console, server);
    const banner = console.locator('#corpus-banner');
    assert.equal(await banner.isHidden(), true);

    const filler = path.join(corpus, 'filler');
    fill(filler);
    let refused = null;
    for (let n = 0; n < 2000 && !refused; n++) {
      await server.trigger('OK', { ref: `t${n}` }).catch((error) => {
        refused = error;
      });
    }
    assert.match(String(refused), /503 .*corpus-unwritable/);
    const told = await operator.waitForEvent((e) => e.type === 'corpus.unwritable');
    await console.locator('#corpus-banner[data-state="failing"]').waitFor({ timeout: DEADLINE_MS });
    assert.equal(await banner.textContent(), told.message);
    assert.match(told.message, /^The corpus disk is full \(.*\): free space on it; triggers are refused until then\./);

    // A console opened now shows the same words (from its welcome).
    const late = await context.newPage();
    await signIn(late, server, 'e2e-late');
    await late.locator('#corpus-banner[data-state="failing"]').waitFor({ timeout: DEADLINE_MS });
    assert.equal(await late.locator('#corpus-banner').textContent(), told.message);
    await late.close();

    fs.rmSync(filler);
    const back = await operator.waitForEvent((e) => e.type === 'corpus.writable');
    await console.locator('#corpus-banner[data-state="told"]').waitFor({ timeout: DEADLINE_MS });
    assert.equal(await banner.textContent(), back.message);
    await server.trigger('OK', { ref: 'after' });
    assert.deepEqual(exceptions, []);
  } finally {
    await context.close();
    await operator?.close();
    await server?.stop();
    execFileSync('umount', ['-l', corpus]);
    removeTemp(scratch);
    removeTemp(bundle);
  }
});
