//! The solution navigator (`gcs navigate`, the ESM paper §4's interface): one self-contained
//! HTML page — no server, no network — with the sketch solved and drawn as SVG, the solve's
//! plan beside it as the DR-plan's tree (the core's nodes, each assembled from its children as
//! rigid bodies, then the closed-form steps), and for each node and step its candidates.
//! Clicking a step shows its candidates as small drawings; picking one shows the realization
//! with that choice and as many of the other choices kept as the realizations allow (the rest
//! re-assembled); "autosolve" goes back to the choices the drawing shows; "download RON" saves
//! the realization shown.
//!
//! The realizations are computed here, not in the page (a pick in the page looks a
//! realization up; it solves nothing): every combination of the core's
//! nodes' real candidates (by homotopy continuation, [`gcs_solve::nodes`]) and of the
//! closed-form steps' candidates under which the consistent redundant constraints still hold
//! ([`gcs_solve::SolveOptions::all`]), at most `limit` of them, each drawn and written as RON
//! in advance.
//!
//! The page keeps its state in `<pre id="state">` as JSON (the realization shown, its choices,
//! its largest residual) and applies `#choose=STEP:K,...` from its address when it loads (STEP
//! as numbered in the plan; `&open=STEP` then shows that step's candidates), which is how the
//! tests drive it.

use gcs_model::System;
use gcs_solve::{Method, SolveOptions};
use serde_json::json;

use crate::{Report, ReportError, picture, run};

/// The page for `system` (read from `file`), with at most `limit` realizations; the core's
/// nodes are enumerated with at most `max_paths` homotopy paths each (0: the core as solved).
///
/// # Errors
/// The analysis or the solve failed, or the solve found no realization to show.
pub fn navigate_page(
    system: &System,
    file: &str,
    limit: usize,
    max_paths: usize,
) -> Result<String, ReportError> {
    let (analysis, backend) = run::solving_analysis(system)?;
    let options = SolveOptions { all: Some(limit.max(1)), max_paths, ..SolveOptions::default() };
    // The nodes' homotopies, kept for the solves of the candidates no listed realization
    // takes: each solves again only the chosen node's parent chain.
    let mut cache = gcs_solve::NodeCache::default();
    let solution = gcs_solve::solve_cached(system, &analysis, &options, &mut cache)
        .map_err(ReportError::Solve)?;
    let report = Report::new(system, file, &analysis, None);
    let nodes = solution.plan.iter().take_while(|p| p.method == Method::Newton).count();
    let (mut realizations, mut choices) = listed(&solution, nodes);
    // The steps with a choice: each node of an enumerated core, each closed-form step.
    let choosable = |p: &gcs_solve::PlanStep| p.method == Method::ClosedForm || p.paths.is_some();
    // When the listing stopped at the limit, a candidate no listed realization takes is still
    // offered: the first realization with it (the others chosen as the solve chooses), one
    // solve each.
    if solution.truncated {
        let mut position = 0;
        for (k, p) in solution.plan.iter().enumerate() {
            if !(k < nodes || p.method == Method::ClosedForm) {
                continue;
            }
            let c = position;
            position += 1;
            if !choosable(p) {
                continue;
            }
            for j in 0..p.candidates {
                if choices.iter().any(|r| r.get(c) == Some(&j)) {
                    continue;
                }
                let options =
                    SolveOptions { all: Some(1), choose: vec![(k, j)], ..options.clone() };
                let Ok(with) = gcs_solve::solve_cached(system, &analysis, &options, &mut cache)
                else {
                    continue;
                };
                let (x, cs) = listed(&with, nodes);
                if let (Some(x), Some(cs)) = (x.into_iter().next(), cs.into_iter().next())
                    && cs.get(c) == Some(&j)
                {
                    realizations.push(x);
                    choices.push(cs);
                }
            }
        }
    }
    let ids = |es: &[gcs_model::EntityIdx]| -> Vec<String> {
        es.iter().map(|e| system.entity(*e).id.clone()).collect()
    };
    let cids = |cs: &[gcs_model::ConstraintIdx]| -> Vec<String> {
        cs.iter().map(|c| system.constraint(*c).id.clone()).collect()
    };
    let drawn: Vec<usize> = (solution.plan.iter().enumerate())
        .filter(|(k, p)| *k < nodes || p.method == Method::ClosedForm)
        .map(|(_, p)| p.chosen.unwrap_or(0))
        .collect();
    let mut shown = Vec::new();
    for (x, c) in realizations.iter().zip(&choices) {
        let solved = gcs_solve::solved_at(system, x);
        shown.push(json!({
            "choices": c,
            "max_residual": gcs_solve::max_relative_residual(system, x, solution.scale),
            "svg": picture::analysis_svg_with_motions(&solved, &report, &[]),
            "ron": solved.to_ron(),
        }));
    }
    if shown.is_empty() {
        return Err(ReportError::Navigate {
            model: system.name().to_owned(),
            why: format!("the solve found no realization (status {})", solution.status.name()),
        });
    }
    let autosolve = choices.iter().position(|c| *c == drawn).unwrap_or(0);
    let mut position = 0;
    let plan: Vec<_> = solution
        .plan
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let choice = (k < nodes || p.method == Method::ClosedForm).then(|| {
                position += 1;
                position - 1
            });
            // The candidates some listed realization takes (a node's depend on its children's
            // choices: the most it has under any of them).
            let offered = choice
                .filter(|_| choosable(p))
                .map(|c| choices.iter().map(|r| r[c] + 1).max().unwrap_or(0));
            json!({
                "step": k,
                "entities": ids(&p.entities),
                "constraints": cids(&p.constraints),
                "method": p.method.name(),
                "candidates": p.candidates,
                "offered": offered,
                "choice": offered.and(choice),
                "children": p.children,
                "paths": p.paths.map(|c| json!({
                    "tracked": c.paths, "finite": c.finite, "real": c.real, "failed": c.failed,
                    "singular": c.singular,
                })),
                "complete": p.complete,
                "incomplete": (p.shortfall.iter())
                    .map(|w| crate::solve::IncompleteReport::new(w).text())
                    .collect::<Vec<_>>(),
            })
        })
        .collect();
    let data = json!({
        "model": system.name(),
        "file": file,
        "backend": backend,
        "status": solution.status.name(),
        "plan": plan,
        "realizations": shown,
        "autosolve": autosolve,
        "truncated": solution.truncated,
    });
    // Inside <script>, "</" would end it.
    let data = data.to_string().replace("</", "<\\/");
    Ok(PAGE.replace("{{TITLE}}", &escape(system.name())).replace("{{DATA}}", &data))
}

/// The realizations a solve lists, with each one's choices: the core's `nodes` nodes', then
/// the closed-form steps'.
fn listed(solution: &gcs_solve::Solution, nodes: usize) -> (Vec<Vec<f64>>, Vec<Vec<usize>>) {
    let realizations: Vec<Vec<f64>> = solution.solutions.clone().unwrap_or_default();
    let node_choices = solution.node_choices.clone().unwrap_or_default();
    let choices = (solution.solution_choices.clone().unwrap_or_default())
        .into_iter()
        .enumerate()
        .map(|(i, closed)| {
            let mut c = node_choices.get(i).cloned().unwrap_or_else(|| vec![0; nodes]);
            c.extend(closed);
            c
        })
        .collect();
    (realizations, choices)
}

/// Text for HTML.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

const PAGE: &str = r#"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>gcs navigate: {{TITLE}}</title>
<style>
body { font-family: sans-serif; margin: 1em; }
#main { display: flex; gap: 2em; align-items: flex-start; }
#picture svg { max-width: 55vw; max-height: 80vh; width: auto; height: auto; border: 1px solid #ccc; }
#plan li { margin: 0.3em 0; }
#plan .node { cursor: pointer; text-decoration: underline dotted; }
#plan .info { color: #666; font-size: 0.9em; }
button.on { font-weight: bold; background: #1f77b4; color: white; }
#note { color: #d62728; min-height: 1.2em; }
#candidates { display: flex; flex-wrap: wrap; gap: 0.5em; }
#candidates figure { margin: 0; cursor: pointer; border: 2px solid #ddd; padding: 2px; }
#candidates figure.on { border-color: #1f77b4; }
#candidates svg { width: 160px; height: auto; max-height: 200px; }
pre#state { background: #f4f4f4; padding: 0.5em; }
</style>
</head>
<body>
<h1>gcs navigate: {{TITLE}}</h1>
<p id="summary"></p>
<p><button id="autosolve">autosolve (the drawing's choices)</button>
<button id="download">download RON</button></p>
<p id="note"></p>
<div id="main">
<div id="picture"></div>
<div><h2>Plan</h2><ol id="plan" start="0"></ol>
<h2 id="candidates-title"></h2><div id="candidates"></div></div>
</div>
<h2>State</h2>
<pre id="state"></pre>
<script type="application/json" id="data">{{DATA}}</script>
<script>
const D = JSON.parse(document.getElementById('data').textContent);
let current = D.autosolve;
let opened = null;
const note = (t) => { document.getElementById('note').textContent = t; };
// The realization that takes `candidate` at choice `c` and changes fewest other choices.
function nearest(c, candidate) {
  const now = D.realizations[current].choices;
  let best = -1, distance = Infinity;
  D.realizations.forEach((r, k) => {
    if (r.choices[c] !== candidate) return;
    const d = r.choices.reduce((n, v, i) => n + (v !== now[i] ? 1 : 0), 0);
    if (d < distance) { distance = d; best = k; }
  });
  return [best, distance];
}
function show(k) {
  current = k;
  const r = D.realizations[k];
  document.getElementById('picture').innerHTML = r.svg;
  document.querySelectorAll('button[data-step]').forEach((b) => {
    const c = D.plan[+b.dataset.step].choice;
    b.classList.toggle('on', r.choices[c] === +b.dataset.candidate);
  });
  document.getElementById('state').textContent = JSON.stringify(
    { realization: k, choices: r.choices, max_residual: r.max_residual }, null, 1);
  if (opened !== null) open(opened);
}
function pick(step, candidate) {
  const c = D.plan[step].choice;
  if (c === null || c === undefined) { note('step ' + step + ' has no choice to make'); return false; }
  const [best, distance] = nearest(c, candidate);
  if (best < 0) {
    note('no realization takes candidate ' + candidate + ' at step ' + step +
      (D.truncated ? ' among those listed (--max-solutions)' : ' (the redundant constraints or the children\'s choices rule it out)'));
    return false;
  }
  note(distance > 1 ? 'other steps changed too: their previous choices have no realization with this one' : '');
  show(best);
  return true;
}
// A step's candidates as small drawings, each the realization picking it would show.
function open(step) {
  opened = step;
  const p = D.plan[step];
  const box = document.getElementById('candidates');
  box.innerHTML = '';
  document.getElementById('candidates-title').textContent = 'Candidates of step ' + step;
  if (p.choice === null || p.choice === undefined) {
    box.textContent = 'one realization: the one solved from the drawing';
    return;
  }
  for (let k = 0; k < p.offered; k++) {
    const [best] = nearest(p.choice, k);
    const f = document.createElement('figure');
    f.classList.toggle('on', D.realizations[current].choices[p.choice] === k);
    f.innerHTML = (best < 0 ? '<p>not with these choices</p>' : D.realizations[best].svg) +
      '<figcaption>candidate ' + k + '</figcaption>';
    if (best >= 0) f.onclick = () => pick(step, k);
    box.appendChild(f);
  }
}
const n = D.realizations.length;
document.getElementById('summary').textContent = D.file + ': ' + n + ' realization' +
  (n === 1 ? '' : 's') + (D.truncated ? ' (more not listed)' : '') + '; status ' + D.status +
  ' (analysis: ' + D.backend + '). Click a step to see its candidates.';
// Depth in the DR-plan: a node's children one deeper.
const depth = D.plan.map(() => 0);
for (let k = D.plan.length - 1; k >= 0; k--) (D.plan[k].children || []).forEach((c) => { depth[c] = depth[k] + 1; });
const plan = document.getElementById('plan');
D.plan.forEach((p) => {
  const li = document.createElement('li');
  li.style.marginLeft = (1.5 * depth[p.step]) + 'em';
  const label = document.createElement('span');
  label.className = 'node';
  label.textContent = p.method + ': ' + p.entities.join(', ') + ' (' + p.constraints.join(', ') + ')';
  label.onclick = () => open(p.step);
  li.appendChild(label);
  const info = [];
  if (p.children && p.children.length) info.push('steps ' + p.children.join(', ') + ' as rigid bodies');
  if (p.paths) info.push(p.paths.real + ' real of ' + p.paths.finite + ' complex, ' + p.paths.tracked + ' paths' +
    (p.paths.failed ? ', ' + p.paths.failed + ' undecided' : ''));
  if (!p.complete && p.incomplete && p.incomplete.length) info.push('not all: ' + p.incomplete.join('; '));
  if (info.length) {
    const i = document.createElement('span');
    i.className = 'info';
    i.textContent = ' [' + info.join('; ') + '] ';
    li.appendChild(i);
  }
  if (p.choice !== null && p.choice !== undefined) {
    for (let k = 0; k < p.offered; k++) {
      const b = document.createElement('button');
      b.textContent = 'candidate ' + k;
      b.dataset.step = p.step; b.dataset.candidate = k;
      b.onclick = () => pick(p.step, k);
      li.appendChild(b);
    }
  } else {
    li.appendChild(document.createTextNode(' (one realization: the one solved from the drawing)'));
  }
  plan.appendChild(li);
});
document.getElementById('autosolve').onclick = () => { note(''); show(D.autosolve); };
document.getElementById('download').onclick = () => {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([D.realizations[current].ron], { type: 'text/plain' }));
  a.download = D.model.replace(/[^A-Za-z0-9_.-]/g, '_') + '.ron';
  a.click();
};
show(current);
const m = /#choose=([0-9:,]+)/.exec(location.hash);
if (m) m[1].split(',').forEach((s) => { const [a, b] = s.split(':').map(Number); pick(a, b); });
const o = /[#&]open=([0-9]+)/.exec(location.hash);
if (o) open(+o[1]);
</script>
</body>
</html>
"#;
