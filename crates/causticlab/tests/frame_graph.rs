//! `render --graph` (GPU on lavapipe, validation on): the frame graph names every pass the
//! frame timed, in order, with what each read and wrote, so that a pass reads what an earlier
//! pass wrote; graph.dot is a digraph with a box per pass; a later render without `--graph`
//! removes the stale graph files; frames through the throughput mode's ring record the same
//! graph.

mod common;

use common::*;

/// The passes of graph.txt: (name, reads, writes).
fn passes(text: &str) -> Vec<(String, Vec<String>, Vec<String>)> {
    text.lines()
        .map(|l| {
            let (head, rest) = l.split_once("  reads: ").unwrap_or_else(|| panic!("no reads in {l:?}"));
            let (reads, writes) = rest.split_once("  writes: ").unwrap_or_else(|| panic!("no writes in {l:?}"));
            let list = |s: &str| if s == "-" { vec![] } else { s.split("; ").map(str::to_string).collect() };
            let name = head.split_whitespace().nth(1).unwrap_or_else(|| panic!("no name in {l:?}")).to_string();
            (name, list(reads), list(writes))
        })
        .collect()
}

#[test]
fn the_frame_graph_shows_each_pass_reading_what_an_earlier_pass_wrote() {
    let dir = scratch("frame-graph");
    let out = dir.join("out").display().to_string();
    let args = |graph: bool| {
        let mut a = vec!["--validate", "render", "--scene", "scenes/sphere_on_plane.toml", "--technique", "wd-points"];
        a.extend(["--photons", "64", "--caustic-map-resolution", "128", "--out", &out]);
        if graph {
            a.push("--graph");
        }
        a.iter().map(|s| s.to_string()).collect::<Vec<String>>()
    };
    let run = causticlab(&args(true));
    assert_eq!(run.code, Some(0), "{}", run.describe());
    assert!(!run.stderr.contains("[validation"), "{}", run.describe());
    let text = std::fs::read_to_string(dir.join("out/graph.txt")).expect("graph.txt");
    assert!(run.stdout.contains(&text), "the graph is printed as written:\n{}", run.describe());
    let graph = passes(&text);
    let position =
        |name: &str| graph.iter().position(|p| p.0 == name).unwrap_or_else(|| panic!("no pass {name}:\n{text}"));
    // The photon buffer is written by its pass, then read by the splat; the caustic map written
    // by the splat is read by the eye's background pass.
    let (buffer, splat, background) =
        (position("photon_buffer.light0"), position("splat.light0"), position("background"));
    assert!(buffer < splat && splat < background, "{text}");
    assert!(graph[buffer].2.contains(&"photon position".to_string()), "{text}");
    assert!(graph[splat].1.contains(&"photon position".to_string()), "{text}");
    assert!(graph[splat].2.contains(&"caustic_map".to_string()), "{text}");
    assert!(graph[background].1.contains(&"caustic_map".to_string()), "{text}");
    // The graph's passes are the passes the render timed, each once (its table lists them by
    // name, from its header to the sum of their medians).
    let timed: Vec<&str> = run
        .stdout
        .lines()
        .skip_while(|l| !l.starts_with("pass "))
        .skip(1)
        .take_while(|l| !l.starts_with("(sum"))
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    let mut names: Vec<&str> = graph.iter().map(|p| p.0.as_str()).collect();
    let mut sorted_timed = timed.clone();
    names.sort();
    sorted_timed.sort();
    assert_eq!(names, sorted_timed, "graph vs timed passes:\n{}", run.stdout);
    let dot = std::fs::read_to_string(dir.join("out/graph.dot")).expect("graph.dot");
    assert!(dot.starts_with("digraph frame {") && dot.ends_with("}\n"), "{dot}");
    for (i, p) in graph.iter().enumerate() {
        assert!(dot.contains(&format!("p{i} [shape=box")) && dot.contains(&format!("{i}: {}", p.0)), "{dot}");
    }
    // Frames through the throughput mode's ring record the same graph, but for the ring's
    // per-slot uniforms (`frame uniforms, slot 1` for `frame uniforms`).
    let mut ring = args(true);
    ring.extend(["--frames", "2", "--frame-mode", "throughput"].map(String::from));
    let run = causticlab(&ring);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    let ring_text = std::fs::read_to_string(dir.join("out/graph.txt")).expect("graph.txt");
    let unslotted = |l: &[String]| -> Vec<String> {
        l.iter().map(|r| r.split(", slot ").next().unwrap_or(r).to_string()).collect()
    };
    let ring_graph: Vec<_> =
        passes(&ring_text).into_iter().map(|(n, r, w)| (n, unslotted(&r), unslotted(&w))).collect();
    assert!(ring_text.contains(", slot "), "the ring's per-slot uniforms:\n{ring_text}");
    assert_eq!(ring_graph, graph, "throughput frames' graph vs a per-pass frame's");
    // Without --graph, the same folder loses the graph of the earlier render.
    let again = causticlab(&args(false));
    assert_eq!(again.code, Some(0), "{}", again.describe());
    assert!(!dir.join("out/graph.txt").exists() && !dir.join("out/graph.dot").exists(), "stale graph files kept");
}
