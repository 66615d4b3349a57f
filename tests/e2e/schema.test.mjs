// The editor schemas (docs/schema/*.json, printed by `docent schema`) checked by an independent
// validator: ajv, on YAML read by the `yaml` package, as VS Code's YAML extension reads it.
// Every shipped bundle's acts files and docent.yaml validate; a typo key, a wrong shortcut, an
// unknown setting and a misspelt command are flagged at their place (ajv's instancePath and the
// key); and `docent check` agrees on each broken copy, so the schema flags no more and no less
// than the loader on these cases.

import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';

import Ajv from 'ajv';
import YAML from 'yaml';

import { docentBin, makeBundle, REPO, removeTemp } from './lib/docent.mjs';

const readSchema = (name) => JSON.parse(fs.readFileSync(path.join(REPO, 'docs/schema', name), 'utf8'));

// strict: unknown keywords or bad patterns in our schemas are errors; union types are on purpose
// (a label may be written as a number, as the loader accepts).
const ajv = new Ajv({ allErrors: true, strict: true, allowUnionTypes: true });
const validateActs = ajv.compile(readSchema('acts.schema.json'));
const validateConfig = ajv.compile(readSchema('docent.schema.json'));

/** ajv's problems for `yamlText` under `validate`: [] when valid. */
function problems(validate, yamlText) {
  const data = YAML.parse(yamlText);
  return validate(data) ? [] : validate.errors;
}

/**
 * `docent check` of a bundle made of `files` (and a home page): the JSON diagnostics, but for
 * `unused-act` (nothing triggers these small bundles' acts; the schema cannot know that).
 */
function check(files) {
  const dir = makeBundle({ 'pages/index.html': '<p>Welcome</p>', ...files });
  try {
    const out = spawnSync(docentBin(), ['check', dir, '--format', 'json'], { encoding: 'utf8' });
    return JSON.parse(out.stdout).filter((d) => d.code !== 'unused-act');
  } finally {
    removeTemp(dir);
  }
}

const GOOD_ACT = '- Label: HELLO\n  Text: Hello there\n';

test('every shipped bundle validates: acts files and docent.yaml', () => {
  const dialogs = path.join(REPO, 'dialogs');
  let files = 0;
  for (const bundle of fs.readdirSync(dialogs)) {
    const dir = path.join(dialogs, bundle);
    if (!fs.statSync(dir).isDirectory()) continue;
    for (const name of fs.readdirSync(dir).filter((n) => /\.ya?ml$/.test(n))) {
      const text = fs.readFileSync(path.join(dir, name), 'utf8');
      const validate = name === 'docent.yaml' ? validateConfig : validateActs;
      assert.deepEqual(problems(validate, text), [], `${bundle}/${name}`);
      files += 1;
    }
  }
  assert.ok(files >= 8, `only ${files} files`);
});

test('a typo key in an act is flagged at that act and key, as docent check does', () => {
  for (const typo of ['Lable', 'label', 'Commands', 'textGroup']) {
    const text = `${GOOD_ACT}- ${typo}: BYE\n  Label: BYE\n  Text: Goodbye\n`.replace(`- ${typo}: BYE\n  Label: BYE`, `- Label: BYE\n  ${typo}: x`);
    const found = problems(validateActs, text).filter((e) => e.keyword === 'additionalProperties');
    assert.deepEqual(
      found.map((e) => [e.instancePath, e.params.additionalProperty]),
      [['/1', typo]],
      typo,
    );
    const checked = check({ 'acts.yaml': text });
    assert.deepEqual(
      checked.map((d) => [d.code, d.line, d.column]),
      [['unknown-key', 4, 3]],
      `${typo}: ${JSON.stringify(checked)}`,
    );
  }
});

test('variant keys in any alphabet are accepted, as the loader accepts them', () => {
  const text = `- Label: HI\n  Text: Hello\n  TextChild: Hi!\n  TextÄltere: Guten Tag\n  Text_2: Hey\n`;
  assert.deepEqual(problems(validateActs, text), []);
  assert.deepEqual(check({ 'acts.yaml': text, 'docent.yaml': 'contexts: [TextChild, TextÄltere, Text_2]\n' }), []);
});

test('a shortcut written as Alt+W is flagged at Key', () => {
  const text = `- Label: WAVE\n  Text: Hello\n  Key: Alt+W\n`;
  const found = problems(validateActs, text);
  assert.ok(found.length > 0);
  assert.ok(found.every((e) => e.instancePath === '/0/Key'), JSON.stringify(found));
  assert.ok(found.some((e) => e.keyword === 'pattern'));
  assert.deepEqual(check({ 'acts.yaml': text }).map((d) => [d.code, d.line]), [['bad-key', 3]]);
  assert.deepEqual(problems(validateActs, `- Label: WAVE\n  Text: Hello\n  Key: w\n`), []);
  assert.deepEqual(problems(validateActs, `- Label: WAVE\n  Text: Hello\n  Key: 7\n`), []);
});

test('a missing label, an empty text and a command the schema knows is wrong are flagged', () => {
  assert.ok(problems(validateActs, `- Text: Hello\n`).some((e) => e.keyword === 'required' && e.params.missingProperty === 'Label'));
  assert.ok(problems(validateActs, `- Label: A\n  Text: []\n`).some((e) => e.instancePath === '/0/Text'));
  for (const bad of ['say hello', 'SAY', 'DRIVE_START now', 'WAIT 2', 'WAIT two seconds']) {
    const text = `- Label: A\n  Cmds:\n    - ${bad}\n`;
    const found = problems(validateActs, text);
    assert.ok(found.some((e) => e.instancePath === '/0/Cmds/0'), `${bad}: ${JSON.stringify(found)}`);
    assert.ok(check({ 'acts.yaml': text }).some((d) => d.severity === 'error' && d.line === 3), bad);
  }
  const good = `- Label: A\n  Cmds:\n    - SAY hello\n    - WAIT\n    - WAIT 1.5s\n    - DRIVE_START\n    - LIGHTS on\n`;
  assert.deepEqual(problems(validateActs, good), []);
  assert.deepEqual(check({ 'acts.yaml': good, 'docent.yaml': 'verbs:\n  LIGHTS:\n' }), []);
});

test('docent.yaml: an unknown setting and a bad value are flagged at their place', () => {
  const found = problems(validateConfig, 'home: index.html\nspeech:\n  rat: 160\n');
  assert.deepEqual(
    found.filter((e) => e.keyword === 'additionalProperties').map((e) => [e.instancePath, e.params.additionalProperty]),
    [['/speech', 'rat']],
  );
  assert.ok(problems(validateConfig, 'hoem: index.html\n').some((e) => e.params.additionalProperty === 'hoem'));
  assert.ok(problems(validateConfig, 'kiosk:\n  idle: 120\n').some((e) => e.instancePath === '/kiosk/idle'));
  assert.ok(problems(validateConfig, 'verbs:\n  SAY: {}\n').length > 0, 'a built-in verb redeclared');
  assert.ok(
    problems(validateConfig, 'server:\n  messages: { max_size: 1048576 }\n').some((e) => e.instancePath === '/server/messages/max_size'),
    'a message size without its unit',
  );
  assert.ok(
    problems(validateConfig, 'server:\n  connections: { per_address: 0 }\n').some((e) => e.instancePath === '/server/connections/per_address'),
    'no connection at all',
  );
  const everything = [
    'home: index.html',
    'contexts: [TextChild]',
    'speech: { adapter: log, voice: en-us, rate: 160 }',
    'display: { adapter: display }',
    'drive: { adapter: sim, speed: 0.5, pose_rate: 5, bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 } }',
    'adapters: { timeout: 30s }',
    'kiosk: { idle: 2m, idle_act: HELLO }',
    'projector: { after_video: hold, highlight_edge: 0.05 }',
    'verbs: { LIGHTS: { adapter: log, argument: required, description: Showcase lights } }',
    'access: { operator_token: op-0123456789abcdef, dm_token: dm-0123456789abcdef }',
    'operator: { camera: "http://cam.local/stream.mjpg", situations: [question, laughter], visitor_groups: { children: TextChild } }',
    'server: { trusted_proxies: [127.0.0.1], connections: { per_address: 256, total: 2048 }, timeouts: { headers: 10s, body: 1m }, messages: { max_size: 4 MiB }, queues: { per_client: 2048 } }',
    '',
  ].join('\n');
  assert.deepEqual(problems(validateConfig, everything), []);
  const acts = `${GOOD_ACT}  TextChild: Hi\n`;
  assert.deepEqual(check({ 'acts.yaml': acts, 'docent.yaml': everything }), []);
});
