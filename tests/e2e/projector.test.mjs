// The projector shell (`GET /projector`) in headless Chromium, and the truth of what it reports:
// a video plays and its end is reported as command.done (so a WAIT sequences speech after the
// film), what follows a film, PROJECT failing with no projector, an unplayable or missing file,
// a picture done only once painted, a reconnecting projector replaying nothing, and the console
// showing the projector's real state. HIGHLIGHT and the poster presenter:
// projector-highlight.test.mjs. An operator websocket client reads the server's events; every
// wait is for an event, with a deadline only.

import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, watchProblems } from './lib/browser.mjs';
import { makeBundle, REPO, removeTemp } from './lib/docent.mjs';
import { signIn } from './lib/operator.mjs';
import { commandIds, openProjector, withProjectorServer } from './lib/projector.mjs';

let browser;
before(async () => {
  browser = await launchBrowser();
});
after(() => browser?.close());

/** Runs `body(ctx)` with a server on `bundle`, a page and an operator (see lib/projector.mjs). */
const withServer = (bundle, body, options) => withProjectorServer(browser, bundle, body, options);

test('a video plays on the projector and its end, reported as command.done, lets a WAIT go on', { timeout: 60_000 }, async () => {
  const clip = path.join(REPO, 'dialogs/museum-tour/media/card-punch.webm');
  const bundle = makeBundle({
    'docent.yaml': 'speech: {adapter: log}\n',
    'acts.yaml': '- Label: FILM\n  Cmds: [PROJECT card-punch.webm, WAIT, SAY After the film]\n',
    'pages/index.html': '<!DOCTYPE html><title>home</title>',
  });
  fs.copyFileSync(clip, path.join(bundle, 'media/card-punch.webm'));
  try {
    await withServer(bundle, async ({ server, page, operator }) => {
      const problems = watchProblems(page);
      await openProjector(page, server, operator);
      const [project, wait, say] = commandIds(await server.trigger('FILM'));

      const started = await operator.waitForEvent((e) => e.type === 'command.started' && e.command === project);
      await page.waitForFunction(() => {
        const video = document.querySelector('video');
        return video && !video.paused && video.currentTime > 0;
      }, null, { timeout: 20_000 });
      const duration = await page.evaluate(() => document.querySelector('video').duration);
      assert.ok(duration > 1 && duration < 30, `the clip lasts ${duration} s`);

      const done = await operator.waitForEvent((e) => e.type === 'command.done' && e.command === project);
      const playedMs = (done.mono_us - started.mono_us) / 1000;
      assert.ok(playedMs >= duration * 1000 * 0.9, `PROJECT done after ${playedMs} ms, the film lasts ${duration} s`);
      const waitDone = await operator.waitForEvent((e) => e.type === 'command.done' && e.command === wait);
      const sent = await operator.waitForEvent((e) => e.type === 'command.sent' && e.command === say);
      assert.ok(done.mono_us <= waitDone.mono_us && waitDone.mono_us <= sent.mono_us);
      assert.equal(sent.arg ?? 'After the film', 'After the film');
      assert.deepEqual(problems, [], 'problems in the projector page');
    });
  } finally {
    removeTemp(bundle);
  }
});

test('with after_video: hold the projector keeps the last frame when a film ends; by default it goes black', { timeout: 90_000 }, async () => {
  const clip = path.join(REPO, 'dialogs/museum-tour/media/card-punch.webm');
  for (const [setting, kept] of [['hold', true], ['black', false]]) {
    const bundle = makeBundle({
      'docent.yaml': `speech: {adapter: log}\nprojector: {after_video: ${setting}}\n`,
      'acts.yaml': '- Label: FILM\n  Cmds: [PROJECT card-punch.webm]\n',
      'pages/index.html': '<!DOCTYPE html><title>home</title>',
    });
    fs.copyFileSync(clip, path.join(bundle, 'media/card-punch.webm'));
    try {
      await withServer(bundle, async ({ server, page, operator }) => {
        await openProjector(page, server, operator);
        const [project] = commandIds(await server.trigger('FILM'));
        await operator.waitForEvent((e) => e.type === 'command.done' && e.command === project);
        // The page answered done from the video's `ended`; what it shows now is settled.
        await page.waitForFunction(() => document.querySelector('video')?.ended ?? true, null, { timeout: 10_000 });
        const shown = await page.evaluate(() => {
          const video = document.querySelector('video');
          return Boolean(video && video.isConnected && getComputedStyle(video).display !== 'none' && !video.hidden);
        });
        assert.equal(shown, kept, `after_video: ${setting}`);
      });
    } finally {
      removeTemp(bundle);
    }
  }
});

test('the paper\'s MPEG-1 film is converted when served, plays on the projector, and PROJECT ends when it ends', { timeout: 90_000 }, async () => {
  // Fig. 4 as printed: `PROJECT Exhibit/video.mpg`, a real MPEG-1 film made here with ffmpeg.
  const bundle = makeBundle({
    'docent.yaml': 'speech: {adapter: log}\n',
    'acts.yaml': '- Label: RUN_VIDEO_EXHIBIT\n  Cmds:\n    - PROJECT Exhibit/video.mpg\n',
    'pages/index.html': '<!DOCTYPE html><title>home</title>',
  });
  const film = path.join(bundle, 'media/Exhibit/video.mpg');
  fs.mkdirSync(path.dirname(film), { recursive: true });
  const made = spawnSync('ffmpeg', ['-v', 'error', '-y', '-f', 'lavfi', '-i', 'testsrc2=size=320x240:rate=25',
    '-f', 'lavfi', '-i', 'sine=frequency=440', '-t', '3', '-c:v', 'mpeg1video', '-c:a', 'mp2', '-f', 'mpeg', film]);
  assert.equal(made.status, 0, `ffmpeg made the film: ${made.stderr}`);
  try {
    await withServer(bundle, async ({ server, page, operator }) => {
      const problems = watchProblems(page);
      // Converted in the background: the operator sees it pending, then a `media` frame
      // without files once it is ready (or nothing pending at all when it was that quick).
      const pending = operator.welcome.state.reload.media ?? [];
      const busy = (files) => files.some((m) => m.state === 'waiting' || m.state === 'converting');
      const settled = busy(pending) ? (await operator.waitFor((f) => f.type === 'media' && !busy(f.files))).files : pending;
      assert.deepEqual(settled, [], 'the film is converted');
      await openProjector(page, server, operator);
      const [project] = commandIds(await server.trigger('RUN_VIDEO_EXHIBIT'));
      const started = await operator.waitForEvent((e) => e.type === 'command.started' && e.command === project);
      const playing = await page.waitForFunction(() => {
        const video = document.querySelector('video');
        return video && !video.paused && video.currentTime > 0 && { duration: video.duration, width: video.videoWidth };
      }, null, { timeout: 20_000 });
      const { duration, width } = await playing.jsonValue();
      assert.ok(Math.abs(duration - 3) < 0.5, `the converted film lasts ${duration} s`);
      assert.equal(width, 320);
      const done = await operator.waitForEvent((e) => e.type === 'command.done' && e.command === project);
      const playedMs = (done.mono_us - started.mono_us) / 1000;
      assert.ok(playedMs >= duration * 1000 * 0.9, `PROJECT done after ${playedMs} ms, the film lasts ${duration} s`);
      assert.deepEqual(problems, [], 'problems in the projector page');
    });
  } finally {
    removeTemp(bundle);
  }
});

test('a PROJECT of a film that cannot be converted fails with the server\'s reason', { timeout: 60_000 }, async () => {
  const bundle = makeBundle({
    'docent.yaml': 'speech: {adapter: log}\n',
    'acts.yaml': '- Label: FILM\n  Cmds: [PROJECT cut.mov]\n',
    'pages/index.html': '<!DOCTYPE html><title>home</title>',
  });
  // A film cut short, as a copy or a download that stopped half way leaves it: a real
  // QuickTime film's first 4 KiB (its `ftyp` and the start of its data, none of its index).
  const whole = path.join(bundle, 'whole.mov');
  const made = spawnSync('ffmpeg', ['-v', 'error', '-y', '-f', 'lavfi', '-i', 'testsrc2=size=320x240:rate=25', '-t', '1', '-c:v', 'mpeg4', whole]);
  assert.equal(made.status, 0, `ffmpeg made the film: ${made.stderr}`);
  fs.writeFileSync(path.join(bundle, 'media/cut.mov'), fs.readFileSync(whole).subarray(0, 4096));
  fs.rmSync(whole);
  try {
    await withServer(bundle, async ({ server, page, operator }) => {
      const pending = operator.welcome.state.reload.media ?? [];
      if (!pending.some((m) => m.state === 'failed')) {
        await operator.waitFor((f) => f.type === 'media' && f.files.some((m) => m.state === 'failed'));
      }
      // The console's banner says it before anyone presses anything, in the server's words.
      const consolePage = await page.context().newPage();
      await signIn(consolePage, server);
      const banner = consolePage.locator('#reload-banner');
      await banner.locator('li[data-state="failed"]').waitFor({ timeout: 10_000 });
      assert.match(await banner.textContent(), /media\/cut\.mov cannot be shown: ffmpeg cannot read it \(/);
      assert.equal(await banner.getAttribute('data-state'), 'refused');
      await openProjector(page, server, operator);
      const [project] = commandIds(await server.trigger('FILM'));
      const failed = await operator.waitForEvent(is('command.failed', project));
      assert.match(failed.reason, /^media\/cut\.mov cannot be shown: ffmpeg cannot read it \(/);
    });
  } finally {
    removeTemp(bundle);
  }
});

/** Makes a bundle of `acts` with a log speech adapter and the shipped clip and picture. */
function mediaBundle(acts, { config = '', extra = {} } = {}) {
  const bundle = makeBundle({
    'docent.yaml': `speech: {adapter: log}\n${config}`,
    'acts.yaml': acts,
    'pages/index.html': '<!DOCTYPE html><title>home</title>',
    ...extra,
  });
  fs.copyFileSync(path.join(REPO, 'dialogs/museum-tour/media/card-punch.webm'), path.join(bundle, 'media/card-punch.webm'));
  fs.copyFileSync(path.join(REPO, 'dialogs/poster-presenter/media/poster.png'), path.join(bundle, 'media/poster.png'));
  return bundle;
}

const is = (type, command) => (e) => e.type === type && e.command === command;

test('PROJECT with no projector connected fails at once, and the WAIT after it reports it', { timeout: 60_000 }, async () => {
  const bundle = mediaBundle('- Label: FILM\n  Cmds: [PROJECT card-punch.webm, WAIT, SAY After the film]\n');
  try {
    await withServer(bundle, async ({ server, operator }) => {
      const [project, wait, say] = commandIds(await server.trigger('FILM'));
      const failed = await operator.waitForEvent(is('command.failed', project));
      assert.equal(failed.reason, 'no projector connected');
      const waitFailed = await operator.waitForEvent(is('command.failed', wait));
      assert.match(waitFailed.reason, /PROJECT/);
      const events = operator.events();
      assert.ok(!events.some(is('command.sent', say)), 'the SAY after the WAIT was not sent');
      assert.ok(!events.some(is('command.started', project)), 'nothing started');
      const state = await server.api('/api/state');
      assert.equal(state.display.projector, null);
    });
  } finally {
    removeTemp(bundle);
  }
});

test('a file the browser cannot play fails the PROJECT with the browser\'s reason and leaves black', { timeout: 60_000 }, async () => {
  const bundle = mediaBundle('- Label: FILM\n  Cmds: [PROJECT broken.webm, WAIT, SAY After the film]\n', {
    extra: { 'media/broken.webm': 'this is not a film at all, only text' },
  });
  try {
    await withServer(bundle, async ({ server, page, operator }) => {
      await openProjector(page, server, operator);
      const [project, wait, say] = commandIds(await server.trigger('FILM'));
      const failed = await operator.waitForEvent(is('command.failed', project));
      assert.match(failed.reason, /^the projector cannot play broken\.webm: \S/);
      console.log(`# the browser's reason: ${failed.reason}`);
      assert.doesNotMatch(failed.reason, /unknown/);
      await operator.waitForEvent(is('command.failed', wait));
      assert.ok(!operator.events().some(is('command.sent', say)));
      assert.equal(await page.evaluate(() => document.getElementById('docent-stage').childElementCount), 0);
      const state = await server.api('/api/state');
      assert.deepEqual([state.display.projector, state.display.projector_state], [null, 'black']);
    });
  } finally {
    removeTemp(bundle);
  }
});

test('a picture or film missing on the server fails the PROJECT with "cannot find"', { timeout: 60_000 }, async () => {
  const bundle = mediaBundle('- Label: PICTURE\n  Cmds: [PROJECT poster.png]\n- Label: FILM\n  Cmds: [PROJECT card-punch.webm]\n');
  try {
    await withServer(bundle, async ({ server, page, operator }) => {
      await openProjector(page, server, operator);
      // Gone since the bundle was loaded: the server answers 404.
      await page.route('**/media/**', (route) => route.fulfill({ status: 404, contentType: 'application/json', body: '{}' }));
      for (const [label, file] of [['PICTURE', 'poster.png'], ['FILM', 'card-punch.webm']]) {
        const [project] = commandIds(await server.trigger(label));
        const failed = await operator.waitForEvent(is('command.failed', project));
        assert.equal(failed.reason, `the projector cannot find ${file} (404 Not Found)`);
      }
      assert.equal(await page.evaluate(() => document.getElementById('docent-stage').childElementCount), 0);
    });
  } finally {
    removeTemp(bundle);
  }
});

test('a picture is done only after the projector reports it painted', { timeout: 60_000 }, async () => {
  const bundle = mediaBundle('- Label: PICTURE\n  Cmds: [PROJECT poster.png, WAIT, SAY After the picture]\n');
  try {
    await withServer(bundle, async ({ server, page, operator }) => {
      const problems = watchProblems(page);
      await openProjector(page, server, operator);
      // The picture's bytes are held back until the test has looked at the events.
      let requested;
      const asked = new Promise((resolve) => (requested = resolve));
      let release;
      const released = new Promise((resolve) => (release = resolve));
      await page.route('**/media/poster.png', async (route) => {
        requested();
        await released;
        await route.continue();
      });
      const [project, wait, say] = commandIds(await server.trigger('PICTURE'));
      await asked;
      await operator.waitForEvent((e) => e.type === 'display.changed' && e.projector_state === 'loading');
      assert.ok(!operator.events().some(is('command.done', project)), 'done before the picture arrived');
      assert.ok(!operator.events().some(is('command.done', wait)), 'the WAIT ended before the picture arrived');
      release();
      const shown = await operator.waitForEvent((e) => e.type === 'display.changed' && e.projector_state === 'shown');
      const done = await operator.waitForEvent(is('command.done', project));
      assert.ok(shown.seq < done.seq);
      await operator.waitForEvent(is('command.sent', say));
      const image = await page.evaluate(() => {
        const img = document.querySelector('#docent-stage img');
        return img && { complete: img.complete, width: img.naturalWidth, loading: img.classList.contains('loading') };
      });
      assert.ok(image && image.complete && image.width > 0 && !image.loading, JSON.stringify(image));
      assert.deepEqual(problems, [], 'problems in the projector page');
    });
  } finally {
    removeTemp(bundle);
  }
});

test('a projector that reconnects after a film ended shows black (or the held frame) and plays nothing', { timeout: 120_000 }, async () => {
  for (const setting of ['black', 'hold']) {
    const bundle = mediaBundle('- Label: FILM\n  Cmds: [PROJECT card-punch.webm]\n- Label: DARK\n  Cmds: [HIGHLIGHT]\n', {
      config: `projector: {after_video: ${setting}}\n`,
    });
    try {
      await withServer(bundle, async ({ server, page, operator }) => {
        await openProjector(page, server, operator);
        const [project] = commandIds(await server.trigger('FILM'));
        await operator.waitForEvent(is('command.started', project));
        await operator.waitForEvent(is('command.done', project));
        const ended = await operator.waitForEvent((e) => e.type === 'display.changed' && ['black', 'held'].includes(e.projector_state));
        assert.equal(ended.projector_state, setting === 'hold' ? 'held' : 'black');

        const media = [];
        page.on('request', (req) => {
          if (req.url().includes('/media/')) media.push(req.url());
        });
        await page.reload();
        await operator.waitForEvent((e) => e.type === 'client.connected' && e.role === 'projector');
        const shown = await page.evaluate(() => {
          const video = document.querySelector('#docent-stage video');
          return video && { paused: video.paused, muted: video.muted, autoplay: video.autoplay };
        });
        if (setting === 'hold') {
          await page.waitForFunction(() => {
            const video = document.querySelector('#docent-stage video');
            return video && video.readyState >= 2 && !video.classList.contains('loading');
          });
          const held = await page.evaluate(() => {
            const video = document.querySelector('#docent-stage video');
            return { paused: video.paused, muted: video.muted, atEnd: video.currentTime >= video.duration - 0.1 };
          });
          assert.deepEqual(held, { paused: true, muted: true, atEnd: true }, 'the held frame, silent and still');
        } else {
          assert.equal(shown, null, 'no video after a reconnect');
          assert.deepEqual(media, [], 'no film loaded after a reconnect');
        }
        // A command after the reconnect is handled after the welcome: then nothing played.
        const [dark] = commandIds(await server.trigger('DARK'));
        await operator.waitForEvent(is('command.done', dark));
        assert.ok(!operator.events().some((e) => e.type === 'command.started' && e.command !== project && e.verb === 'PROJECT'));
        const playing = await page.evaluate(() => [...document.querySelectorAll('video')].some((v) => !v.paused));
        assert.equal(playing, false, 'nothing plays');
      });
    } finally {
      removeTemp(bundle);
    }
  }
});

test('the console shows what the projector reported: not shown yet, playing, then black', { timeout: 90_000 }, async () => {
  const bundle = mediaBundle('- Label: FILM\n  Cmds: [PROJECT card-punch.webm]\n');
  try {
    await withServer(bundle, async ({ server, page, operator }) => {
      const consolePage = await page.context().newPage();
      await signIn(consolePage, server);
      const cell = consolePage.locator('#projector-content');
      assert.equal(await cell.getAttribute('data-state'), 'black');
      assert.equal(await cell.textContent(), 'black');
      // No projector yet: the PROJECT fails and the console keeps showing black.
      const [missed] = commandIds(await server.trigger('FILM'));
      await operator.waitForEvent(is('command.failed', missed));
      assert.equal(await cell.textContent(), 'black');

      await openProjector(page, server, operator);
      // The film's bytes are held back: the console must say it is not on screen yet.
      let release;
      const released = new Promise((resolve) => (release = resolve));
      await page.route('**/media/card-punch.webm', async (route) => {
        await released;
        await route.continue();
      });
      const [project] = commandIds(await server.trigger('FILM'));
      await consolePage.locator('#projector-content[data-state="loading"]').waitFor();
      assert.equal(await cell.textContent(), 'card-punch.webm · not shown yet');
      release();
      await operator.waitForEvent(is('command.started', project));
      await consolePage.locator('#projector-content[data-state="playing"]').waitFor();
      assert.equal(await cell.textContent(), 'card-punch.webm · playing');
      await operator.waitForEvent(is('command.done', project));
      await consolePage.locator('#projector-content[data-state="black"]').waitFor();
      assert.equal(await cell.textContent(), 'black');
    });
  } finally {
    removeTemp(bundle);
  }
});
