//! The solution navigator (`gcs navigate`, the ESM paper §4's interface, for the closed-form
//! steps): one self-contained HTML page — no server, no network — with the sketch solved and
//! drawn as SVG, the solve's plan beside it, and for each closed-form step its candidates.
//! Picking a candidate shows the realization with that choice and as many of the other
//! choices kept as the realizations allow (the rest re-assembled); "autosolve" goes back to the
//! choices the drawing shows; "download RON" saves the realization shown.
//!
//! The realizations are computed here, not in the page: every combination of the closed-form
//! steps' real candidates under which the consistent redundant constraints still hold
//! ([`gcs_solve::SolveOptions::all`]), at most `limit` of them, each drawn and written as RON
//! in advance. The core (what no closed-form step places) is the one solved from the drawing:
//! its other realizations are not enumerated (no homotopy yet).
//!
//! The page keeps its state in `<pre id="state">` as JSON (the realization shown, its choices,
//! its largest residual) and applies `#choose=STEP:K,...` from its address when it loads (STEP
//! as numbered in the plan), which is how the tests drive it.

use gcs_model::System;
use gcs_solve::{Method, SolveOptions};
use serde_json::json;

use crate::{Report, ReportError, picture, run};

/// The page for `system` (read from `file`), with at most `limit` realizations.
///
/// # Errors
/// The analysis or the solve failed, or the solve found no realization to show.
pub fn navigate_page(system: &System, file: &str, limit: usize) -> Result<String, ReportError> {
    let (analysis, backend) = run::solving_analysis(system)?;
    // (The page offers the closed-form steps' choices, the core as solved: its other
    // realizations are not computed.)
    let options = SolveOptions { all: Some(limit.max(1)), max_paths: 0, ..SolveOptions::default() };
    let solution = gcs_solve::solve(system, &analysis, &options).map_err(ReportError::Solve)?;
    let report = Report::new(system, file, &analysis, None);
    // The page chooses among the closed-form steps' candidates: the core as solved from the
    // drawing (its first realization).
    let cores = solution.core_choices.clone().unwrap_or_default();
    let on_solved_core = |i: &usize| cores.get(*i).is_none_or(|k| *k == 0);
    let realizations: Vec<Vec<f64>> = (solution.solutions.clone().unwrap_or_default().into_iter())
        .enumerate()
        .filter(|(i, _)| on_solved_core(i))
        .map(|(_, x)| x)
        .collect();
    let choices: Vec<Vec<usize>> =
        (solution.solution_choices.clone().unwrap_or_default().into_iter())
            .enumerate()
            .filter(|(i, _)| on_solved_core(i))
            .map(|(_, c)| c)
            .collect();
    let steps: Vec<(usize, &gcs_solve::PlanStep)> =
        solution.plan.iter().enumerate().filter(|(_, p)| p.method == Method::ClosedForm).collect();
    let ids = |es: &[gcs_model::EntityIdx]| -> Vec<String> {
        es.iter().map(|e| system.entity(*e).id.clone()).collect()
    };
    let cids = |cs: &[gcs_model::ConstraintIdx]| -> Vec<String> {
        cs.iter().map(|c| system.constraint(*c).id.clone()).collect()
    };
    let drawn: Vec<usize> = steps.iter().map(|(_, p)| p.chosen.unwrap_or(0)).collect();
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
    let plan: Vec<_> = solution
        .plan
        .iter()
        .enumerate()
        .map(|(k, p)| {
            json!({
                "step": k,
                "entities": ids(&p.entities),
                "constraints": cids(&p.constraints),
                "method": p.method.name(),
                "candidates": p.candidates,
                "choice": steps.iter().position(|(i, _)| *i == k),
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
#picture svg { max-width: 60vw; height: auto; border: 1px solid #ccc; }
#plan li { margin: 0.3em 0; }
button.on { font-weight: bold; background: #1f77b4; color: white; }
#note { color: #d62728; min-height: 1.2em; }
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
<div><h2>Plan</h2><ol id="plan" start="0"></ol></div>
</div>
<h2>State</h2>
<pre id="state"></pre>
<script type="application/json" id="data">{{DATA}}</script>
<script>
const D = JSON.parse(document.getElementById('data').textContent);
let current = D.autosolve;
const note = (t) => { document.getElementById('note').textContent = t; };
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
}
function pick(step, candidate) {
  const c = D.plan[step].choice;
  if (c === null || c === undefined) { note('step ' + step + ' is not a closed-form step'); return false; }
  const now = D.realizations[current].choices;
  let best = -1, distance = Infinity;
  D.realizations.forEach((r, k) => {
    if (r.choices[c] !== candidate) return;
    const d = r.choices.reduce((n, v, i) => n + (v !== now[i] ? 1 : 0), 0);
    if (d < distance) { distance = d; best = k; }
  });
  if (best < 0) {
    note('no realization takes candidate ' + candidate + ' at step ' + step +
      (D.truncated ? ' among those listed (--max-solutions)' : ' (the redundant constraints rule it out)'));
    return false;
  }
  note(distance > 1 ? 'other steps changed too: their previous choices have no realization with this one' : '');
  show(best);
  return true;
}
document.getElementById('summary').textContent = D.file + ': ' + D.realizations.length +
  ' realization' + (D.realizations.length === 1 ? '' : 's') + (D.truncated ? ' (more not listed)' : '') +
  ' of the closed-form steps, the core as solved from the drawing; status ' + D.status +
  ' (analysis: ' + D.backend + ')';
const plan = document.getElementById('plan');
D.plan.forEach((p) => {
  const li = document.createElement('li');
  li.appendChild(document.createTextNode(p.method + ': ' + p.entities.join(', ') + ' (' +
    p.constraints.join(', ') + ') '));
  if (p.choice !== null && p.choice !== undefined) {
    for (let k = 0; k < p.candidates; k++) {
      const b = document.createElement('button');
      b.textContent = 'candidate ' + k;
      b.dataset.step = p.step; b.dataset.candidate = k;
      b.onclick = () => pick(p.step, k);
      li.appendChild(b);
    }
  } else {
    li.appendChild(document.createTextNode('(one realization: the one solved from the drawing)'));
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
</script>
</body>
</html>
"#;
