// The kiosk recorder's split of a piece of recording larger than the server's chunk limit
// (static/recorder.js, `splitChunk`): consecutive pieces, none over the limit, whose
// concatenation is the piece itself, so uploading them as consecutive chunks loses nothing.
// Plain Node (its Blob is the browser's), no browser needed.

import { test } from 'node:test';
import assert from 'node:assert/strict';

import { splitChunk } from '../../static/recorder.js';

const bytes = (n) => Uint8Array.from({ length: n }, (_, i) => (i * 7 + 3) % 251);

test('a piece over the limit becomes consecutive chunks that concatenate to it', async () => {
  const whole = bytes(25);
  const pieces = splitChunk(new Blob([whole]), 8);
  assert.deepEqual(pieces.map((p) => p.size), [8, 8, 8, 1]);
  const joined = new Uint8Array(await new Blob(pieces).arrayBuffer());
  assert.deepEqual(joined, whole);
});

test('a piece within the limit, or exactly at it, stays one chunk; an empty one none', () => {
  assert.deepEqual(splitChunk(new Blob([bytes(8)]), 8).map((p) => p.size), [8]);
  assert.deepEqual(splitChunk(new Blob([bytes(3)]), 8).map((p) => p.size), [3]);
  assert.deepEqual(splitChunk(new Blob([]), 8), []);
  assert.throws(() => splitChunk(new Blob([bytes(3)]), 0), RangeError);
});
