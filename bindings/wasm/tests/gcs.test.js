// Tests of the WASM package (run `bash bindings/wasm/build.sh` first): its reports equal the
// CLI's JSON lines on every shipped example (the "one API" proof), CAD bytes, errors, options.
// The CLI is $GCS_CLI when set, else target/release/gcs (or $CARGO_TARGET_DIR/release/gcs).
'use strict';
const test = require('node:test');
const assert = require('node:assert/strict');
const fs = require('node:fs');
const path = require('node:path');
const { execFileSync, spawnSync } = require('node:child_process');

const gcs = require('../pkg');
const root = path.resolve(__dirname, '..', '..', '..');

function cli() {
  if (process.env.GCS_CLI) return process.env.GCS_CLI;
  const target = process.env.CARGO_TARGET_DIR || path.join(root, 'target');
  const exe = path.join(target, 'release', 'gcs');
  if (!fs.existsSync(exe)) {
    execFileSync('cargo', ['build', '--release', '-q', '-p', 'gcs-cli'], { cwd: root, stdio: 'inherit' });
  }
  return exe;
}

// The CLI's JSON lines on `data`, run in the repository root so `file` fields match.
function cliLines(...args) {
  const out = spawnSync(cli(), [...args, '--format', 'json', 'data'], { cwd: root, encoding: 'utf8', maxBuffer: 1 << 28 });
  assert.ok(out.status === 0 || out.status === 1, out.stderr);
  return out.stdout.split('\n').filter((l) => l).map((l) => JSON.parse(l));
}

// Every example file, in the CLI's order (sorted paths).
function examples() {
  const files = [];
  const walk = (dir) => {
    for (const e of fs.readdirSync(path.join(root, dir), { withFileTypes: true })) {
      const rel = `${dir}/${e.name}`;
      if (e.isDirectory()) walk(rel);
      else if (/\.(ron|slvs|fcstd|json)$/i.test(e.name)) files.push(rel);
    }
  };
  walk('data');
  return files.sort();
}

// The package's objects for every model of every example: `analyzeAll` for analyze, and one
// call per sketch for the others (a failure as {error} to compare with the CLI's).
function packageLines(run) {
  const lines = [];
  for (const file of examples()) {
    const bytes = fs.readFileSync(path.join(root, file));
    const names = gcs.analyzeAll(bytes, { file, backend: 'float' }).map((r) => r.model);
    for (const sketch of names) {
      try {
        lines.push(run(bytes, { file, sketch }));
      } catch (e) {
        lines.push({ file, jsError: e.message });
      }
    }
  }
  return lines;
}

// Equal as data; a number that is not an integer may differ in its last bits: the solver's
// doubles (residuals, solved coordinates) are computed by the same code, but WebAssembly's
// floating point (scalar reductions, Rust's libm) is not x86-64's (faer's SIMD reductions, the
// system libm). Everything else (ranks, ids, verdicts, exact fields) must be identical.
function sameData(a, b, where = '') {
  if (typeof a === 'number' && typeof b === 'number' && !(Number.isInteger(a) && Number.isInteger(b))) {
    const scale = Math.max(1e-6, Math.abs(a), Math.abs(b));
    assert.ok(Math.abs(a - b) <= 1e-9 * scale, `${where}: ${a} vs ${b}`);
    return;
  }
  if (Array.isArray(a) && Array.isArray(b)) {
    assert.equal(b.length, a.length, `${where}: lengths`);
    a.forEach((x, i) => sameData(x, b[i], `${where}[${i}]`));
    return;
  }
  if (a && b && typeof a === 'object' && typeof b === 'object') {
    assert.deepEqual(Object.keys(b), Object.keys(a), `${where}: fields`);
    for (const k of Object.keys(a)) sameData(a[k], b[k], `${where}.${k}`);
    return;
  }
  assert.strictEqual(b, a, where);
}

function compare(cliOut, pkgOut) {
  assert.ok(cliOut.length > 0);
  assert.equal(pkgOut.length, cliOut.length);
  cliOut.forEach((c, i) => {
    const p = pkgOut[i];
    if (p.jsError !== undefined) {
      assert.ok(c.error && c.error.includes(p.jsError), `${c.error} / ${p.jsError}`);
    } else {
      sameData(c, p, `${c.file} ${c.model}`);
    }
  });
}

test('analyzeAll equals gcs analyze on every example', () => {
  const cliOut = cliLines('analyze');
  const pkgOut = examples().flatMap((file) => gcs.analyzeAll(fs.readFileSync(path.join(root, file)), { file }));
  sameData(cliOut, pkgOut);
});

test('analyze with options equals the CLI with its flags', () => {
  const cliOut = cliLines('analyze', '--structural', '--decompose', '--backend', 'modp', '--seed', '7');
  compare(cliOut, packageLines((b, o) => gcs.analyze(b, { ...o, structural: true, decompose: true, backend: 'modp', seed: 7 })));
});

test('solve equals gcs solve on every example', () => {
  compare(cliLines('solve'), packageLines((b, o) => gcs.solve(b, o)));
});

test('check equals gcs check on every example', () => {
  compare(cliLines('check'), packageLines((b, o) => gcs.check(b, o)));
});

test('the kite from a string', () => {
  const text = fs.readFileSync(path.join(root, 'data/paper/kite.ron'), 'utf8');
  const r = gcs.analyze(text);
  assert.equal(r.file, '<string>');
  assert.equal(r.model, 'kite');
  assert.equal(r.dof, 0);
  assert.equal(r.rank, 5);
  assert.deepEqual(r.redundant.map((x) => x.constraint), ['c6']);
  assert.deepEqual(r.redundant[0].spanning_group, ['c1', 'c2', 'c3', 'c4', 'c5']);
  const s = gcs.solve(text, { file: 'kite.ron' });
  assert.equal(s.status, 'solved');
});

test('errors name the file, line and id', () => {
  const bad = 'System(dim: 2, entities: [Point(id: "p")],\n    constraints: [Fix(id: "f", a: "q")])';
  assert.throws(() => gcs.analyze(bad, { file: 'bad.ron' }), (e) => {
    assert.match(e.message, /^bad\.ron:2:\d+: constraint "f": field a: unknown entity id "q"$/);
    return true;
  });
  assert.throws(() => gcs.analyze('System(dim: 2)', { backend: 'quantum' }), /backend "quantum"/);
  assert.throws(() => gcs.analyze('System(dim: 2)', { colour: 'red' }), /options: unknown field `colour`/);
  assert.throws(() => gcs.analyze(42), /expected a string or a Uint8Array/);
  const plate = fs.readFileSync(path.join(root, 'data/cad/plate.FCStd'));
  assert.throws(() => gcs.analyze(plate, { file: 'plate.FCStd', sketch: 'Nope' }), /no sketch named "Nope"; its models: plate\/Sketch/);
});

test('the ES-module import works in node', async () => {
  const m = await import(path.join(__dirname, '..', 'pkg', 'node', 'gcs_wasm.js'));
  const f = m.analyze ?? m.default.analyze;
  const r = f('System(dim: 2, entities: [Point(id: "p", at: [0, 0])])');
  assert.deepEqual([r.unknowns, r.dof_absolute, r.dof], [2, 2, 0]);
});
