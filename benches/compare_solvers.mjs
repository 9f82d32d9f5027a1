// FreeCAD's PlaneGCS (the npm package @salusoft89/planegcs, compiled to WebAssembly) on
// sketches written by `cargo run --release -p gcs-solve --example export_drawn` (JSON), for
// benches/compare_solvers.sh: one line per file in the format of gcs's `solve_json` example.
// Usage: node benches/compare_solvers.mjs FILE...   (GCS_CMP_NPM: the directory where the
// package is installed, default /work/npm-cmp; VERBOSE=1: the diagnosis on stderr; GCS_CMP_PIN=0: nothing held).
// The sketch: a point per point (the `fixed` one with fixed: true), a p2p_distance per
// distance, and a coordinate_x/coordinate_y constraint for the pinned coordinate; solved from
// the drawing with the wrapper's default algorithm (DogLeg) and default options.
import { readFileSync, existsSync } from "node:fs";
import { join } from "node:path";
import { pathToFileURL } from "node:url";

const npm = process.env.GCS_CMP_NPM || "/work/npm-cmp";
const entry = join(npm, "node_modules/@salusoft89/planegcs/dist/index.js");
if (!existsSync(entry)) {
  console.error(
    `compare_solvers.mjs: PlaneGCS not found at ${entry}; install it with ` +
      `'mkdir -p ${npm} && cd ${npm} && npm install @salusoft89/planegcs' or set GCS_CMP_NPM`,
  );
  process.exit(2);
}
const { init_planegcs_module, GcsWrapper, SolveStatus } = await import(pathToFileURL(entry).href);
const version = JSON.parse(
  readFileSync(join(npm, "node_modules/@salusoft89/planegcs/package.json"), "utf8"),
).version;
const mod = await init_planegcs_module();
const statusName = Object.fromEntries(Object.entries(SolveStatus).map(([k, v]) => [v, k]));

// The triangles of the graph of distances: triples a < b < c joined pairwise.
function triangles(n, edges) {
  const adjacent = Array.from({ length: n }, () => new Set());
  for (const [u, v] of edges) {
    if (u !== v) {
      adjacent[u].add(v);
      adjacent[v].add(u);
    }
  }
  const out = [];
  for (let a = 0; a < n; a++) {
    for (const b of adjacent[a]) {
      if (b <= a) continue;
      for (const c of adjacent[b]) {
        if (c > b && adjacent[a].has(c)) out.push([a, b, c]);
      }
    }
  }
  return out;
}
const turn = (p, a, b, c) =>
  (p[b][0] - p[a][0]) * (p[c][1] - p[a][1]) - (p[b][1] - p[a][1]) * (p[c][0] - p[a][0]);

for (const file of process.argv.slice(2)) {
  const sketch = JSON.parse(readFileSync(file, "utf8"));
  const { points, distances, fixed, pin } = sketch;
  let t = process.hrtime.bigint();
  const gcs = new GcsWrapper(new mod.GcsSystem());
  const pinned = process.env.GCS_CMP_PIN !== "0";
  const fixedSet = new Set(pinned ? fixed : []);
  const primitives = points.map(([x, y], i) => ({
    id: `p${i}`,
    type: "point",
    x,
    y,
    fixed: fixedSet.has(i),
  }));
  distances.forEach(([i, j, value], k) =>
    primitives.push({ id: `d${k}`, type: "p2p_distance", p1_id: `p${i}`, p2_id: `p${j}`, distance: value }),
  );
  const axis = pin.axis;
  if (pinned) primitives.push({
    id: "pin",
    type: `coordinate_${axis}`,
    p_id: `p${pin.point}`,
    [axis]: points[pin.from][axis === "x" ? 0 : 1] + pin.offset,
  });
  gcs.push_primitives_and_params(primitives);
  const setup = Number(process.hrtime.bigint() - t) / 1e9;
  t = process.hrtime.bigint();
  const status = gcs.solve();
  const solve = Number(process.hrtime.bigint() - t) / 1e9;
  gcs.apply_solution();
  const x = points.map((_, i) => {
    const p = gcs.sketch_index.get_primitive(`p${i}`);
    return [p.x, p.y];
  });
  let residual = 0;
  for (const [i, j, value] of distances) {
    residual = Math.max(residual, Math.abs(Math.hypot(x[i][0] - x[j][0], x[i][1] - x[j][1]) - value));
  }
  const tri = triangles(points.length, distances);
  const kept = tri.filter(([a, b, c]) => turn(points, a, b, c) * turn(x, a, b, c) > 0).length;
  if (process.env.VERBOSE) {
    console.error(
      `planegcs ${version} ${sketch.name}: dof ${gcs.gcs.dof()} ` +
        `redundant [${gcs.get_gcs_redundant_constraints()}] ` +
        `partially redundant [${gcs.get_gcs_partially_redundant_constraints()}] ` +
        `conflicting [${gcs.get_gcs_conflicting_constraints()}]`,
    );
  }
  console.log(
    `tool=planegcs${pinned ? "" : "-free"} n=${points.length} seed=${sketch.seed} jitter=${sketch.jitter} ` +
      `setup=${setup.toFixed(3)}s solve=${solve.toFixed(3)}s status=${statusName[status]} ` +
      `max_residual=${residual.toExponential(1)} orientation_kept=${kept}/${tri.length}`,
  );
  gcs.destroy_gcs_module();
}
