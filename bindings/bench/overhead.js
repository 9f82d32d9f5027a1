// Time of the WASM package on every example in data/, against the CLI: min of N runs.
// Usage: node bindings/bench/overhead.js [N]   (GCS_CLI: the CLI, default target/release/gcs)
const fs = require('fs'); const path = require('path'); const { spawnSync } = require('child_process');
const gcs = require('../wasm/pkg');
const n = Number(process.argv[2] || 5);
const root = path.resolve(__dirname, '..', '..'); process.chdir(root);
const cli = process.env.GCS_CLI || 'target/release/gcs';
const files = [];
const walk = (d) => { for (const e of fs.readdirSync(d, { withFileTypes: true })) { const p = `${d}/${e.name}`; if (e.isDirectory()) walk(p); else if (/\.(ron|slvs|fcstd|json)$/i.test(e.name)) files.push(p); } };
walk('data'); files.sort();
const best = (f) => { let m = Infinity; for (let i = 0; i < n; i++) { const s = process.hrtime.bigint(); f(); m = Math.min(m, Number(process.hrtime.bigint() - s) / 1e6); } return m; };
const tCli = best(() => spawnSync(cli, ['analyze', '--format', 'json', '--jobs', '1', 'data']));
const tJs = best(() => { for (const f of files) gcs.analyzeAll(fs.readFileSync(f), { file: f }); });
console.log(`${files.length} files: CLI (one process, --jobs 1) ${tCli.toFixed(0)} ms; WASM in node ${tJs.toFixed(0)} ms (${(tJs / tCli).toFixed(2)}x)`);
