// The two content pages the browser benchmarks switch between (tap-paint, key-paint), made
// here so the benchmarks need no media files: a heading, a paragraph and a picture each, like
// an exhibit page, and two large controls at the same place on both pages: a `data-act`
// button (the kiosk's way: the act shows the other page) and a plain `<a href>` to the other
// page (the floor: the browser's own navigation). The controls are positioned absolutely so a
// tap at the same point hits the same control on either page.
//
// Each page carries a small inline script that times its own showing, used when the page is
// opened directly (the floor): a `pointerdown` anywhere stores the tap's time in
// sessionStorage, and `window.__painted` resolves once the page has loaded and painted, with
// epoch times in ms (performance.timeOrigin + a time on the page's own clock, so times taken
// in two documents can be subtracted; bench/README.md gives the error of that).

import zlib from 'node:zlib';

/** Where the controls are (CSS px from the page's top left) and their size. */
export const BUTTON = { x: 48, y: 600, width: 300, height: 120 };
export const LINK = { x: 420, y: 600, width: 300, height: 120 };

/** The middle of a control: where a finger lands. */
export function middle(box) {
  return { x: box.x + box.width / 2, y: box.y + box.height / 2 };
}

const PROBE = `<script>
addEventListener('pointerdown', (e) => {
  sessionStorage.setItem('tapAt', String(performance.timeOrigin + e.timeStamp));
}, { capture: true });
window.__painted = new Promise((resolve) => {
  const at = {};
  const done = () => { if (at.painted !== undefined && at.fcp !== undefined) resolve(at); };
  new PerformanceObserver((list) => {
    for (const e of list.getEntries()) {
      if (e.name === 'first-contentful-paint') { at.fcp = performance.timeOrigin + e.startTime; done(); }
    }
  }).observe({ type: 'paint', buffered: true });
  addEventListener('load', () => requestAnimationFrame(() => {
    at.painted = performance.timeOrigin + performance.now();
    at.navStart = performance.timeOrigin;
    at.tapAt = Number(sessionStorage.getItem('tapAt'));
    done();
  }));
});
</script>`;

const box = (b) => `position:absolute;left:${b.x}px;top:${b.y}px;width:${b.width}px;height:${b.height}px`;

/** One page, `other` being the page its controls lead to (`b` for page `a`). */
export function pageHtml(name, other, colour) {
  const title = `Page ${name.toUpperCase()}`;
  return (
    `<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>${title}</title>\n${PROBE}\n` +
    `<style>body{margin:0;padding:48px;font:24px/1.4 system-ui,sans-serif;background:${colour}}` +
    `h1{font-size:56px;margin:0 0 24px}img{display:block;width:480px;height:300px}` +
    `.control{box-sizing:border-box;display:flex;align-items:center;justify-content:center;border:0;` +
    `border-radius:16px;background:#234;color:#fff;font:28px system-ui,sans-serif;text-decoration:none}` +
    `</style></head>\n<body><h1>${title}</h1><p>A small content page for the speed benchmarks: a ` +
    `heading, a paragraph of text and a picture, like an exhibit page.</p>` +
    `<img src="../media/${name}.png" alt="${title}">\n` +
    `<button class="control" style="${box(BUTTON)}" data-act="SHOW_${other.toUpperCase()}">Show ${other}</button>\n` +
    `<a class="control" style="${box(LINK)}" href="${other}.html">Go to ${other}</a>\n</body></html>\n`
  );
}

/**
 * The floor's switch: a tap on the link of the page open in `floor` (opened directly, not in
 * the shell) to `target`; resolves with that page's `__painted` times once it has loaded.
 * The tab is brought to the front first: Chromium gives a tab behind another no animation
 * frames.
 */
export async function floorSwitch(floor, target, deadlineMs) {
  await floor.bringToFront();
  const at = middle(LINK);
  await floor.touchscreen.tap(at.x, at.y);
  await floor.waitForURL(`**/pages/${target}`, { timeout: deadlineMs });
  return floor.evaluate(() => window.__painted);
}

/** The bundle: pages a.html and b.html, their pictures, and the acts SHOW_A and SHOW_B. */
export function twoPageBundle(extraActs = '') {
  return {
    // No kiosk.idle: each DISPLAY_PAGE counts as activity, so the 2 min default never fires.
    'docent.yaml': 'home: a.html\n',
    'acts.yaml':
      '- Label: SHOW_A\n  Cmds:\n    - DISPLAY_PAGE a.html\n' +
      '- Label: SHOW_B\n  Cmds:\n    - DISPLAY_PAGE b.html\n' +
      extraActs,
    'pages/a.html': pageHtml('a', 'b', '#f4efe6'),
    'pages/b.html': pageHtml('b', 'a', '#e6eef4'),
    'media/a.png': png(480, 300, [200, 60, 40], [250, 200, 80]),
    'media/b.png': png(480, 300, [30, 80, 160], [90, 200, 170]),
  };
}

// A small PNG (RGB, a two-colour gradient) made here, so the benches need no media files.
export function png(width, height, [r0, g0, b0], [r1, g1, b1]) {
  const row = 1 + width * 3;
  const raw = Buffer.alloc(row * height);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const t = (x + y) / (width + height);
      const o = y * row + 1 + x * 3;
      raw[o] = r0 + (r1 - r0) * t;
      raw[o + 1] = g0 + (g1 - g0) * t;
      raw[o + 2] = b0 + (b1 - b0) * t;
    }
  }
  const chunk = (type, data) => {
    const len = Buffer.alloc(4);
    len.writeUInt32BE(data.length);
    const body = Buffer.concat([Buffer.from(type, 'ascii'), data]);
    const crc = Buffer.alloc(4);
    crc.writeUInt32BE(crc32(body));
    return Buffer.concat([len, body, crc]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0);
  ihdr.writeUInt32BE(height, 4);
  ihdr[8] = 8; // bit depth
  ihdr[9] = 2; // truecolour
  return Buffer.concat([
    Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
    chunk('IHDR', ihdr),
    chunk('IDAT', zlib.deflateSync(raw)),
    chunk('IEND', Buffer.alloc(0)),
  ]);
}

function crc32(buf) {
  let c = ~0;
  for (const byte of buf) {
    c ^= byte;
    for (let k = 0; k < 8; k++) c = (c >>> 1) ^ (0xedb88320 & -(c & 1));
  }
  return ~c >>> 0;
}
