// The robot's live camera in the operator console, in headless Chromium: the kiosk shell (`/`)
// answers the console's (`/operator`) WebRTC call with Chromium's fake camera and microphone,
// signalled through Docent's websocket, and the console's <video> shows moving pictures; a
// second console shares the camera, a kiosk that reconnects is called again, the camera is
// released when the consoles hang up, and a kiosk without a camera says why. The launcher's own
// switch (kiosk/launch.sh) opens the camera without the test-only fake permission prompt. A
// camera URL in docent.yaml shows a real MJPEG stream served by this test, retried after an
// error. Kiosks that share a name are told apart, and one of them is never called in the
// place of another without the operator's choice. Every wait is for an event or a page state,
// with a deadline only.

import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import http from 'node:http';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { launchBrowser, newTouchContext, watchProblems } from './lib/browser.mjs';
import { copyBundle, DEADLINE_MS, REPO, removeTemp, startDocent, withDeadline } from './lib/docent.mjs';
import { openShell } from './lib/kiosk.mjs';
import { newConsoleContext, signIn } from './lib/operator.mjs';

/** Chromium's fake camera and microphone, granted without a prompt; host candidates on loopback. */
const FAKE_MEDIA = ['--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream', '--allow-loopback-in-peer-connection'];
const BUNDLE = path.join(REPO, 'dialogs/info-terminal');

let browser;
before(async () => {
  browser = await launchBrowser(FAKE_MEDIA);
});
after(() => browser?.close());

/** Runs `body` with a server on `bundle`; stops it after. */
async function withServer(bundle, body) {
  const server = await startDocent(bundle);
  try {
    await body(server);
  } finally {
    await server.stop();
  }
}

/** Opens the operator console in a new context of `inBrowser` and signs in. */
async function openConsole(inBrowser, server) {
  const context = await newConsoleContext(inBrowser);
  const page = await context.newPage();
  const problems = watchProblems(page);
  await signIn(page, server, 'camera-test');
  return { context, page, problems };
}

/** Opens the kiosk shell in a new touch context; `init` runs in its pages before their scripts. */
async function openKiosk(inBrowser, server, init = recordMedia) {
  const context = await newTouchContext(inBrowser);
  await context.addInitScript(init);
  const page = await context.newPage();
  const problems = watchProblems(page);
  await openShell(page, server, 'index.html');
  return { context, page, problems };
}

// Runs in the kiosk before its scripts: counts getUserMedia calls and keeps the streams, so the
// test can see the camera shared and released.
function recordMedia() {
  const media = navigator.mediaDevices;
  const original = media.getUserMedia.bind(media);
  window.e2eMedia = { calls: 0, streams: [] };
  media.getUserMedia = async (constraints) => {
    window.e2eMedia.calls += 1;
    const stream = await original(constraints);
    window.e2eMedia.streams.push(stream);
    return stream;
  };
}

/** Waits until the console's camera panel is in `state` (`live`, `error`, ...); returns its text. */
async function cameraState(page, state, timeout = DEADLINE_MS) {
  try {
    await page.locator(`#camera[data-state="${state}"]`).waitFor({ state: 'attached', timeout });
  } catch (e) {
    const now = await page.locator('#camera').evaluate((el) => `${el.dataset.state}: ${el.textContent}`);
    throw new Error(`the camera panel did not become ${state} (it is ${now}): ${e.message}`);
  }
  return page.locator('#camera .camera-state').textContent();
}

/** Waits for `count` new video frames in the console; returns their media times and the size. */
function videoFrames(page, count) {
  return page.locator('#camera video').evaluate(
    (video, n) =>
      new Promise((resolve) => {
        const times = [];
        const step = (_now, meta) => {
          times.push(meta.mediaTime);
          if (times.length >= n) resolve({ times, width: video.videoWidth, height: video.videoHeight });
          else video.requestVideoFrameCallback(step);
        };
        video.requestVideoFrameCallback(step);
      }),
    count,
    { timeout: DEADLINE_MS },
  );
}

/**
 * Waits until the console's received sound is not silent (Chromium's fake microphone beeps);
 * returns the loudest sample seen, 0..1.
 */
function soundArrives(page) {
  return page.locator('#camera video').evaluate(
    (video) =>
      new Promise((resolve) => {
        const audio = new AudioContext();
        const analyser = audio.createAnalyser();
        audio.createMediaStreamSource(video.srcObject).connect(analyser);
        const samples = new Float32Array(analyser.fftSize);
        const listen = () => {
          analyser.getFloatTimeDomainData(samples);
          const peak = samples.reduce((max, x) => Math.max(max, Math.abs(x)), 0);
          if (peak > 0.05) {
            audio.close();
            resolve(peak);
          } else {
            requestAnimationFrame(listen);
          }
        };
        listen();
      }),
    null,
    { timeout: DEADLINE_MS },
  );
}

/** The live tracks the console receives: `['audio', 'video']` when both arrive. */
function receivedTracks(page) {
  return page.locator('#camera video').evaluate((video) =>
    (video.srcObject?.getTracks() ?? []).filter((t) => t.readyState === 'live').map((t) => t.kind).sort(),
  );
}

test('the console shows the kiosk camera over WebRTC, shared by two consoles, called again after the kiosk reconnects', { timeout: 120_000 }, async (t) => {
  await withServer(BUNDLE, async (server) => {
    const kiosk = await openKiosk(browser, server);
    const consoles = [];
    try {
      assert.equal(await kiosk.page.locator('body').getAttribute('data-camera'), 'webrtc');
      const first = await openConsole(browser, server);
      consoles.push(first);
      const text = await cameraState(first.page, 'live');
      assert.match(text, /^live from kiosk/);
      const frames = await videoFrames(first.page, 10);
      assert.deepEqual([frames.width, frames.height], [640, 480], 'the fake camera is 640x480');
      assert.ok(frames.times.at(-1) > frames.times[0], `the picture does not move: ${frames.times}`);
      assert.deepEqual(await receivedTracks(first.page), ['audio', 'video']);
      const peak = await soundArrives(first.page);
      // The sound starts muted (no gesture yet); the operator turns it on.
      const sound = first.page.locator('#camera .camera-sound');
      assert.equal(await first.page.locator('#camera video').evaluate((v) => v.muted), true);
      await sound.click();
      assert.equal(await first.page.locator('#camera video').evaluate((v) => v.muted), false);
      assert.equal(await sound.textContent(), 'Sound off');
      const firstFrameMs = Number(await first.page.locator('#camera').getAttribute('data-first-frame-ms'));
      const fps = (frames.times.length - 1) / (frames.times.at(-1) - frames.times[0]);
      t.diagnostic(`offer to first frame: ${firstFrameMs} ms; ${fps.toFixed(1)} frames/s; sound peak ${peak.toFixed(2)}`);

      // A second console shares the camera: the kiosk opened it once.
      const second = await openConsole(browser, server);
      consoles.push(second);
      await cameraState(second.page, 'live');
      await videoFrames(second.page, 3);
      assert.equal(await kiosk.page.evaluate(() => window.e2eMedia.calls), 1, 'getUserMedia called more than once');

      // The kiosk reloads (a new client id): both consoles call it again by themselves.
      assert.deepEqual(kiosk.problems, [], 'problems in the kiosk shell');
      const before = await first.page.locator('#camera .camera-state').textContent();
      await kiosk.page.reload();
      await openShell(kiosk.page, server, 'index.html');
      for (const { page } of consoles) {
        await page.waitForFunction(
          (old) => {
            const el = document.querySelector('#camera');
            return el.dataset.state === 'live' && el.querySelector('.camera-state').textContent !== old;
          },
          before,
          { timeout: DEADLINE_MS },
        );
        await videoFrames(page, 3);
      }
      t.diagnostic(`after the kiosk reconnected: ${await first.page.locator('#camera .camera-state').textContent()}`);

      // Both consoles go: the kiosk releases its camera and microphone.
      for (const c of consoles.splice(0)) {
        assert.deepEqual(c.problems, [], 'problems in a console');
        await c.context.close();
      }
      const closed = Date.now();
      await kiosk.page.waitForFunction(
        () => window.e2eMedia.streams.length > 0 && window.e2eMedia.streams.every((s) => s.getTracks().every((tr) => tr.readyState === 'ended')),
        null,
        { timeout: DEADLINE_MS },
      );
      t.diagnostic(`camera released ${Date.now() - closed} ms after the last console closed`);
      // (Reloading cancels the page the kiosk was loading: no problem of its own.)
      const aborted = (p) => /^request failed: .*\(net::ERR_ABORTED\)$/.test(p);
      assert.deepEqual(kiosk.problems.filter((p) => !aborted(p)), [], 'problems in the kiosk shell');
    } finally {
      for (const c of consoles) await c.context.close();
      await kiosk.context.close();
    }
  });
});

test('kiosks of one name are told apart by their ids, with a warning; when the kiosk called leaves, the console asks instead of calling the other', { timeout: 120_000 }, async () => {
  await withServer(BUNDLE, async (server) => {
    const one = await openKiosk(browser, server);
    const operator = await openConsole(browser, server);
    const two = await openKiosk(browser, server);
    const { page } = operator;
    try {
      await cameraState(page, 'live');
      // Both kiosk shells are called "kiosk": the picker names them by their ids and warns.
      const picker = page.locator('#camera .camera-pick');
      await picker.waitFor({ state: 'visible' });
      await page.waitForFunction(() => document.querySelectorAll('#camera .camera-pick option').length === 2);
      const options = await picker.locator('option').evaluateAll((os) => os.map((o) => ({ value: o.value, text: o.textContent })));
      for (const o of options) assert.equal(o.text, `kiosk (#${o.value})`);
      const warning = page.locator('#camera .camera-warning');
      assert.equal(await warning.isVisible(), true, 'no warning about the shared name');
      assert.match(await warning.textContent(), new RegExp(`2 kiosks are called “kiosk”: only their numbers \\(#${options[0].value}, #${options[1].value}\\)`));
      // The first is called; the second, seen beside it, is another device.
      assert.equal(await one.page.evaluate(() => window.e2eMedia.calls), 1);
      assert.equal(await two.page.evaluate(() => window.e2eMedia.calls), 0);

      // The kiosk called goes away: the console does not call the other one by their shared name.
      await one.context.close();
      const text = await cameraState(page, 'choose');
      assert.match(text, /left; another kiosk is called “kiosk”: choose the one to watch/);
      assert.equal(await picker.isVisible(), true);
      assert.equal(await two.page.evaluate(() => window.e2eMedia.calls), 0, 'the other kiosk was called without asking');

      // The operator chooses it: called; the picker lets go of the focus (typing goes to the search).
      await picker.focus();
      await picker.selectOption(options[1].value);
      await cameraState(page, 'live');
      assert.equal(await two.page.evaluate(() => window.e2eMedia.calls), 1);
      assert.notEqual(await page.evaluate(() => document.activeElement?.className), 'camera-pick');
      assert.equal(await warning.isVisible(), false, 'a warning with one kiosk left');
      assert.deepEqual(operator.problems, [], 'problems in the console');
    } finally {
      await operator.context.close();
      await two.context.close();
      await one.context.close().catch(() => {});
    }
  });
});

test('a kiosk without a camera tells the console why', { timeout: 60_000 }, async () => {
  await withServer(BUNDLE, async (server) => {
    const kiosk = await openKiosk(browser, server, () => {
      navigator.mediaDevices.getUserMedia = () =>
        Promise.reject(new DOMException('Requested device not found', 'NotFoundError'));
    });
    const operator = await openConsole(browser, server);
    try {
      const text = await cameraState(operator.page, 'error');
      assert.equal(text, 'no camera on the kiosk: NotFoundError: Requested device not found');
      assert.equal(await operator.page.locator('#camera .camera-retry').isVisible(), true, 'no way to try again');
    } finally {
      await operator.context.close();
      await kiosk.context.close();
    }
  });
});

test("with kiosk/launch.sh's switch the kiosk opens its camera without a permission prompt", { timeout: 60_000 }, async () => {
  const dryRun = execFileSync(path.join(REPO, 'kiosk/launch.sh'), ['--dry-run', '--chromium', 'chromium'], {
    encoding: 'utf8',
    env: { ...process.env, DISPLAY: '', HOME: '/home/kiosk', DOCENT_URL: 'http://127.0.0.1:8080' },
    stdio: ['ignore', 'pipe', 'ignore'],
  });
  const [touch, projector] = dryRun.split('/kiosk/watchdog.sh').slice(1);
  const camera = '--auto-accept-camera-and-microphone-capture';
  assert.ok(touch.includes(camera), `the touchscreen browser lacks ${camera}:\n${touch}`);
  assert.ok(!projector.includes(camera), `the projector browser has ${camera}`);

  // A kiosk browser as the launcher starts it (fake devices, but no fake permission prompt).
  const kioskBrowser = await launchBrowser(['--use-fake-device-for-media-stream', '--allow-loopback-in-peer-connection', camera]);
  try {
    await withServer(BUNDLE, async (server) => {
      const kiosk = await openKiosk(kioskBrowser, server);
      const operator = await openConsole(browser, server);
      try {
        await cameraState(operator.page, 'live');
        await videoFrames(operator.page, 3);
        assert.equal(await kiosk.page.evaluate(() => window.e2eMedia.calls), 1);
      } finally {
        await operator.context.close();
        await kiosk.context.close();
      }
    });
  } finally {
    await kioskBrowser.close();
  }
});

/** Serves `/stream.mjpg`: `multipart/x-mixed-replace` JPEG frames, after `failures` 503 answers. */
async function mjpegServer(frames, failures) {
  const requests = [];
  const streams = []; // per stream answered: a promise that resolves when its connection closes
  const sockets = new Set();
  const server = http.createServer((req, res) => {
    requests.push(req.url);
    if (req.url !== '/stream.mjpg' || requests.length <= failures) {
      res.writeHead(req.url === '/stream.mjpg' ? 503 : 404).end();
      return;
    }
    const boundary = 'docentframe';
    res.writeHead(200, {
      'content-type': `multipart/x-mixed-replace; boundary=${boundary}`,
      'cache-control': 'no-cache',
    });
    let i = 0;
    const send = () => {
      const jpeg = frames[i++ % frames.length];
      res.write(`--${boundary}\r\ncontent-type: image/jpeg\r\ncontent-length: ${jpeg.length}\r\n\r\n`);
      res.write(jpeg);
      res.write('\r\n');
    };
    send();
    // A camera sends pictures at its own pace: ten a second here.
    const timer = setInterval(send, 100);
    streams.push(new Promise((resolve) => res.on('close', resolve)));
    res.on('close', () => clearInterval(timer));
  });
  server.on('connection', (socket) => {
    sockets.add(socket);
    socket.on('close', () => sockets.delete(socket));
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return {
    url: `http://127.0.0.1:${server.address().port}/stream.mjpg`,
    requests,
    streams,
    close: () => {
      for (const socket of sockets) socket.destroy();
      return new Promise((resolve) => server.close(resolve));
    },
  };
}

test('a camera URL shows its MJPEG stream, tried again after the camera failed to answer', { timeout: 60_000 }, async () => {
  // Two real JPEG pictures, made by the browser itself.
  const context = await browser.newContext({ viewport: { width: 320, height: 240 } });
  const painter = await context.newPage();
  const frames = [];
  for (const colour of ['#c33', '#36c']) {
    await painter.setContent(`<body style="margin:0;background:${colour}"><h1 style="color:#fff">camera</h1></body>`);
    frames.push(await painter.screenshot({ type: 'jpeg', quality: 80 }));
  }
  await context.close();

  const camera = await mjpegServer(frames, 1);
  const bundle = copyBundle('info-terminal', {
    'docent.yaml': `home: index.html\nspeech: { voice: en, rate: 150 }\noperator: { camera: "${camera.url}" }\n`,
  });
  try {
    await withServer(bundle, async (server) => {
      const shell = await (await fetch(`${server.base}/`)).text();
      assert.ok(!shell.includes('data-camera'), 'the kiosk answers camera calls although the camera is a URL');
      const operator = await openConsole(browser, server);
      try {
        await cameraState(operator.page, 'live');
        const picture = await operator.page.locator('#camera img').evaluate((img) => ({
          src: img.src,
          width: img.naturalWidth,
          height: img.naturalHeight,
        }));
        assert.deepEqual(picture, { src: camera.url, width: 320, height: 240 });
        assert.deepEqual(camera.requests.slice(0, 2), ['/stream.mjpg', '/stream.mjpg'], 'no second attempt after the 503');

        // Reload (for a stream that froze): a new stream, and the old one's connection ends.
        await operator.page.locator('#camera .camera-retry').click();
        await withDeadline(camera.streams[0], DEADLINE_MS, 'the first stream was not closed after Reload');
        await cameraState(operator.page, 'live');
        assert.equal(camera.streams.length, 2, `streams answered: ${camera.streams.length}`);
        assert.deepEqual(operator.problems.filter((p) => !p.includes('503')), [], 'problems in the console');
      } finally {
        await operator.context.close();
      }
    });
  } finally {
    await withDeadline(camera.close(), DEADLINE_MS, 'the MJPEG server did not close');
    removeTemp(bundle);
  }
});
