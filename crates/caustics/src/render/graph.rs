//! The frame graph: every pass of a recorded frame in order with the resources it read and
//! wrote, as vkcore recorded them from each pass's declarations (the descriptors it binds and
//! the uses it declares: the same declarations its barriers come from), written as text and as
//! Graphviz DOT (`causticlab render --graph`).

use std::fmt::Write as _;
use vkcore::PassNode;

/// One line per pass: `index  name  reads: a; b  writes: c` (`;` between resources: a
/// resource's name may hold a comma, `frame uniforms, slot 1`).
pub fn text(graph: &[PassNode]) -> String {
    let width = graph.iter().map(|p| p.name.len()).max().unwrap_or(0);
    let mut out = String::new();
    for (i, p) in graph.iter().enumerate() {
        let list = |l: &[String]| if l.is_empty() { "-".to_string() } else { l.join("; ") };
        let _ = writeln!(out, "{i:>3}  {:<width$}  reads: {}  writes: {}", p.name, list(&p.reads), list(&p.writes));
    }
    out
}

/// A DOT digraph: passes as boxes, in recording order; each write of a resource is a new
/// version of it (an ellipse), and a pass that reads the resource reads its latest version, so
/// the graph has no cycles and shows which pass's output each pass reads. Resources that no
/// pass of the frame writes (uniforms, meshes, textures: the frame's inputs) are listed in one
/// note rather than drawn with an edge to every pass that reads them (`text` has every one).
pub fn dot(graph: &[PassNode], title: &str) -> String {
    // A quoted DOT string: backslashes and quotes escaped, line breaks as DOT's `\n`.
    let q = |s: &str| format!("\"{}\"", s.replace('\\', "\\\\").replace('"', "\\\"").replace('\n', "\\n"));
    let mut out = String::new();
    let _ = writeln!(out, "digraph frame {{");
    let _ = writeln!(out, "  label={}; labelloc=t; rankdir=TB; fontname=\"Helvetica\";", q(title));
    let _ = writeln!(out, "  node [fontname=\"Helvetica\", fontsize=10]; edge [color=\"#555555\"];");
    let written = |r: &String| graph.iter().any(|p| p.writes.contains(r));
    let mut inputs: Vec<&String> = vec![];
    for r in graph.iter().flat_map(|p| &p.reads).filter(|r| !written(r)) {
        if !inputs.contains(&r) {
            inputs.push(r);
        }
    }
    if !inputs.is_empty() {
        let names: Vec<&str> = inputs.iter().map(|s| s.as_str()).collect();
        let _ = writeln!(
            out,
            "  inputs [shape=note, label={}];",
            q(&format!("read, not written, this frame:\n{}", names.join("\n")))
        );
    }
    // The latest version of each resource: its node id.
    let mut latest: Vec<(String, String)> = vec![];
    let mut versions = 0usize;
    for (i, p) in graph.iter().enumerate() {
        let pass = format!("p{i}");
        let _ = writeln!(
            out,
            "  {pass} [shape=box, style=filled, fillcolor=\"#dde8f5\", label={}];",
            q(&format!("{i}: {}", p.name))
        );
        for r in p.reads.iter().filter(|r| written(r)) {
            let id = match latest.iter().find(|(n, _)| n == r) {
                Some((_, id)) => id.clone(),
                None => {
                    // Read before any pass of this frame wrote it: what the resource held
                    // before the frame (uploaded, the previous frame's, or a cleared
                    // attachment's declared read: declarations name accesses, not load ops).
                    versions += 1;
                    let id = format!("r{versions}");
                    let _ = writeln!(out, "  {id} [shape=ellipse, style=dashed, label={}];", q(r));
                    latest.push((r.clone(), id.clone()));
                    id
                }
            };
            let _ = writeln!(out, "  {id} -> {pass};");
        }
        for w in &p.writes {
            versions += 1;
            let id = format!("r{versions}");
            let _ = writeln!(out, "  {id} [shape=ellipse, label={}];", q(w));
            let _ = writeln!(out, "  {pass} -> {id};");
            match latest.iter_mut().find(|(n, _)| n == w) {
                Some(entry) => entry.1 = id,
                None => latest.push((w.clone(), id)),
            }
        }
    }
    out.push_str("}\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node(name: &str, reads: &[&str], writes: &[&str]) -> PassNode {
        let v = |l: &[&str]| l.iter().map(|s| s.to_string()).collect();
        PassNode { name: name.into(), reads: v(reads), writes: v(writes) }
    }

    #[test]
    fn each_write_is_a_new_version_that_later_reads_come_from() {
        let g = [
            node("splat", &["photons", "caustic_map"], &["caustic_map"]),
            node("blur", &["caustic_map"], &["caustic_map"]),
            node("eye", &["caustic_map"], &["final"]),
        ];
        let d = dot(&g, "t");
        // photons: read, never written: in the inputs' note, no node of its own; caustic_map
        // read by splat before any write (dashed: what it held before the frame), then written twice:
        // r2 by splat, r3 by blur.
        for edge in ["r1 -> p0;", "p0 -> r2;", "r2 -> p1;", "p1 -> r3;", "r3 -> p2;", "p2 -> r4;"] {
            assert!(d.contains(edge), "{edge} missing:\n{d}");
        }
        assert!(d.contains("inputs [shape=note, label=\"read, not written, this frame:\\nphotons\"]"), "{d}");
        assert!(!d.contains("label=\"photons\""), "{d}");
        assert!(!d.contains("r2 -> p2"), "the eye reads the blurred map, not the splatted one:\n{d}");
        let t = text(&g);
        assert_eq!(t.lines().nth(1), Some("  1  blur   reads: caustic_map  writes: caustic_map"));
        assert!(
            t.lines().next().is_some_and(|l| l.contains("reads: photons; caustic_map  writes: caustic_map")),
            "{t}"
        );
    }
}
