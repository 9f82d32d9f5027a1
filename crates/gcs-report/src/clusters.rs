//! Clusters and W-decompositions in reports: as data (format §2 `clusters`, §3
//! `decomposition`), as text trees, and as a Graphviz DOT graph.

use gcs_analysis::{Cluster, DecompositionNode, GlobalRigidity, GroupRigidity};
use gcs_model::{ConstraintIdx, EntityIdx, System};
use serde::{Deserialize, Serialize};

/// A cluster (format §2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ClusterReport {
    /// Its entities, in file order.
    pub entities: Vec<String>,
    /// The constraints among them, in file order.
    pub constraints: Vec<String>,
    /// Whether its own points and distances determine its shape (global rigidity, the
    /// stress-matrix test); absent for a cluster that is not a distance framework.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub globally_rigid: Option<bool>,
}

/// A node of a W-decomposition (format §3).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NodeReport {
    /// Its entities, in file order.
    pub entities: Vec<String>,
    /// The constraints among them.
    pub constraints: Vec<String>,
    /// The rigid subsystems it decomposes into.
    pub children: Vec<NodeReport>,
    /// The declared groups (ids) this node is (extension; absent when none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub groups: Vec<String>,
}

/// A declared group as the W-decomposition took it (format §3, `groups`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GroupReport {
    /// Its id.
    pub id: String,
    /// Whether it is rigid on its own constraints (those among its entities): then it is a
    /// node of the DR-plan.
    pub rigid: bool,
    /// Its maximal rigid subsystems on its own constraints (1 when rigid).
    pub parts: usize,
}

/// The groups' verdicts as report data.
pub fn groups_report(system: &System, groups: &[GroupRigidity]) -> Vec<GroupReport> {
    (groups.iter())
        .map(|g| GroupReport {
            id: system.groups()[g.group].id.clone(),
            rigid: g.rigid(),
            parts: g.parts,
        })
        .collect()
}

/// The groups that are not nodes of the DR-plan, as text lines (a rigid group is marked in the
/// tree).
pub fn groups_text(system: &System, groups: &[GroupRigidity]) -> Vec<String> {
    (groups.iter())
        .filter(|g| !g.rigid())
        .map(|g| {
            format!(
                "    group {} is not rigid on its own constraints ({} rigid parts): not a node",
                system.groups()[g.group].id,
                g.parts
            )
        })
        .collect()
}

fn entity_ids(system: &System, es: &[EntityIdx]) -> Vec<String> {
    es.iter().map(|e| system.entity(*e).id.clone()).collect()
}

fn constraint_ids(system: &System, cs: &[ConstraintIdx]) -> Vec<String> {
    cs.iter().map(|c| system.constraint(*c).id.clone()).collect()
}

/// The clusters as report data, each with its global rigidity (`global`, in the same order;
/// missing entries count as not covered).
pub fn clusters_report(
    system: &System,
    clusters: &[Cluster],
    global: &[Option<GlobalRigidity>],
) -> Vec<ClusterReport> {
    clusters
        .iter()
        .enumerate()
        .map(|(k, c)| ClusterReport {
            entities: entity_ids(system, &c.entities),
            constraints: constraint_ids(system, &c.constraints),
            globally_rigid: global.get(k).and_then(|g| g.as_ref().map(|g| g.globally_rigid)),
        })
        .collect()
}

/// The clusters that can flip (not globally rigid, of more than one entity) as text lines.
pub fn flips_text(
    system: &System,
    clusters: &[Cluster],
    global: &[Option<GlobalRigidity>],
) -> Vec<String> {
    clusters
        .iter()
        .zip(global)
        .filter(|(c, g)| c.entities.len() > 1 && g.as_ref().is_some_and(|g| !g.globally_rigid))
        .map(|(c, _)| {
            format!(
                "  can flip (its dimensions admit other shapes): {{{}}}",
                short(system, &c.entities)
            )
        })
        .collect()
}

/// A decomposition tree as report data.
pub fn tree_report(system: &System, node: &DecompositionNode) -> NodeReport {
    NodeReport {
        entities: entity_ids(system, &node.entities),
        constraints: constraint_ids(system, &node.constraints),
        children: node.children.iter().map(|c| tree_report(system, c)).collect(),
        groups: node.groups.iter().map(|g| system.groups()[*g].id.clone()).collect(),
    }
}

/// Entity ids of a set, segments and B-splines left out when their points are in it (they add
/// nothing to read), abbreviated when long.
fn short(system: &System, es: &[EntityIdx]) -> String {
    let ids: Vec<&str> = es
        .iter()
        .filter(|e| {
            !system.entity(**e).kind().is_composite()
                || !system.entity(**e).geometry.parts().iter().all(|p| es.contains(p))
        })
        .map(|e| system.entity(*e).id.as_str())
        .collect();
    const MAX: usize = 12;
    if ids.len() <= MAX {
        ids.join(", ")
    } else {
        format!("{}, … ({} entities)", ids[..MAX].join(", "), ids.len())
    }
}

/// The clusters as text lines.
pub fn clusters_text(system: &System, clusters: &[Cluster]) -> Vec<String> {
    let mut out = Vec::new();
    let shared = |e: &EntityIdx| clusters.iter().filter(|c| c.entities.contains(e)).count() > 1;
    // Entities rigid with nothing else are listed together, at the end.
    let alone: Vec<&str> = clusters
        .iter()
        .filter(|c| c.entities.len() == 1)
        .map(|c| system.entity(c.entities[0]).id.as_str())
        .collect();
    for c in clusters.iter().filter(|c| c.entities.len() > 1) {
        let hinges: Vec<&str> = c
            .entities
            .iter()
            .filter(|e| shared(e) && !system.entity(**e).kind().is_composite())
            .map(|e| system.entity(*e).id.as_str())
            .collect();
        let mut line = format!(
            "  rigid: {{{}}} ({} constraint{}",
            short(system, &c.entities),
            c.constraints.len(),
            if c.constraints.len() == 1 { "" } else { "s" }
        );
        if c.grounded {
            line.push_str(", held in place");
        }
        if !hinges.is_empty() {
            line.push_str(&format!(", hinged at {}", hinges.join(", ")));
        }
        line.push(')');
        out.push(line);
    }
    if !alone.is_empty() {
        const MAX: usize = 16;
        let list = if alone.len() <= MAX {
            alone.join(", ")
        } else {
            format!("{}, … ({} in all)", alone[..MAX].join(", "), alone.len())
        };
        out.push(format!("  rigidly attached to nothing: {list}"));
    }
    out
}

/// A decomposition tree as indented text lines.
pub fn tree_text(system: &System, node: &DecompositionNode, out: &mut Vec<String>) {
    fn walk(
        system: &System,
        node: &DecompositionNode,
        prefix: &str,
        last: bool,
        root: bool,
        out: &mut Vec<String>,
    ) {
        let label = format!(
            "{{{}}} {} constraint{}{}",
            short(system, &node.entities),
            node.constraints.len(),
            if node.constraints.len() == 1 { "" } else { "s" },
            if node.children.is_empty() { ", W-indecomposable" } else { "" }
        );
        let label = match node.groups.as_slice() {
            [] => label,
            groups => {
                let ids: Vec<&str> =
                    groups.iter().map(|g| system.groups()[*g].id.as_str()).collect();
                format!("{label} (group {})", ids.join(", "))
            }
        };
        if root {
            out.push(format!("    {label}"));
        } else {
            out.push(format!("    {prefix}{}{label}", if last { "└─ " } else { "├─ " }));
        }
        let child_prefix = if root {
            String::new()
        } else {
            format!("{prefix}{}", if last { "   " } else { "│  " })
        };
        for (i, c) in node.children.iter().enumerate() {
            walk(system, c, &child_prefix, i + 1 == node.children.len(), false, out);
        }
    }
    walk(system, node, "", true, true, out);
}

fn dot_escape(s: &str) -> String {
    s.replace('\\', "\\\\").replace('"', "\\\"")
}

/// The W-decomposition as a Graphviz digraph: one node per rigid subsystem, labelled with its
/// entity ids, and an edge from each subsystem to the subsystems it decomposes into.
pub fn dot(system: &System, trees: &[DecompositionNode]) -> String {
    fn walk(
        system: &System,
        node: &DecompositionNode,
        next: &mut usize,
        out: &mut String,
    ) -> usize {
        let id = *next;
        *next += 1;
        let ids: Vec<&str> = node
            .entities
            .iter()
            .filter(|e| !system.entity(**e).kind().is_composite())
            .map(|e| system.entity(*e).id.as_str())
            .collect();
        // Wrap the label every eight ids.
        let label = ids.chunks(8).map(|c| c.join(" ")).collect::<Vec<_>>().join("\\n");
        let shape = if node.children.is_empty() { "box" } else { "box, style=bold" };
        out.push_str(&format!(
            "  n{id} [label=\"{}\\n({} constraints)\", shape={shape}];\n",
            dot_escape(&label).replace("\\\\n", "\\n"),
            node.constraints.len()
        ));
        for c in &node.children {
            let child = walk(system, c, next, out);
            out.push_str(&format!("  n{id} -> n{child};\n"));
        }
        id
    }
    let mut out = format!(
        "digraph \"{}\" {{\n  rankdir=TB;\n  node [fontname=\"Helvetica\"];\n",
        dot_escape(system.name())
    );
    let mut next = 0;
    for t in trees {
        walk(system, t, &mut next, &mut out);
    }
    out.push_str("}\n");
    out
}
