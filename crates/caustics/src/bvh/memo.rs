//! [`vertex_thickness`], computed once per mesh in a process. A bench config makes a renderer
//! per cell (two for a cell with a throughput metric), and each uploads the scene's meshes: on
//! the Stanford dragon (250k triangles, 125k vertices) the BVH and a ray per vertex cost the
//! CPU about as much as the cell's frames on lavapipe, and Table 1 of Wyman & Davis 2006 has 96
//! cells on dragon scenes. The thickness depends on the mesh alone, so the last few meshes'
//! are kept, each found by comparing the whole mesh (not a hash of it).

use super::vertex_thickness;
use glam::Vec3;
use std::sync::{Arc, Mutex};

/// How many meshes are remembered: a scene has a few refractors (Table 1's Ball & Dragon and
/// Two Dragons, two or three), so a run over its scenes keeps finding them. About 6.5 MB each
/// for the dragon.
const KEPT: usize = 6;

struct Entry {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    indices: Vec<u32>,
    thickness: Arc<[f32]>,
}

/// The meshes remembered, oldest first.
#[derive(Default)]
struct Memo(Vec<Entry>);

impl Memo {
    fn find(&self, positions: &[Vec3], normals: &[Vec3], indices: &[u32]) -> Option<Arc<[f32]>> {
        let e = self.0.iter().find(|e| e.positions == positions && e.normals == normals && e.indices == indices)?;
        Some(e.thickness.clone())
    }

    /// Remembers `thickness` for the mesh (once), forgetting the oldest past `kept`.
    fn keep(&mut self, positions: &[Vec3], normals: &[Vec3], indices: &[u32], thickness: &Arc<[f32]>, kept: usize) {
        if self.find(positions, normals, indices).is_some() {
            return;
        }
        if self.0.len() >= kept {
            self.0.remove(0);
        }
        let (positions, normals, indices) = (positions.to_vec(), normals.to_vec(), indices.to_vec());
        self.0.push(Entry { positions, normals, indices, thickness: thickness.clone() });
    }
}

static MEMO: Mutex<Memo> = Mutex::new(Memo(Vec::new()));

/// [`vertex_thickness`] of the mesh, the same values, computed only the first time this
/// process asks for this mesh (among the last [`KEPT`] asked for).
pub fn vertex_thickness_memo(positions: &[Vec3], normals: &[Vec3], indices: &[u32]) -> Arc<[f32]> {
    // A thread that panicked while holding the lock left the list whole (a push or a remove),
    // so a poisoned lock is used as it is.
    let lock = || MEMO.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(t) = lock().find(positions, normals, indices) {
        return t;
    }
    // Computed without the lock: two threads asking for one new mesh each compute it once.
    let thickness: Arc<[f32]> = vertex_thickness(positions, normals, indices).into();
    lock().keep(positions, normals, indices, &thickness, KEPT);
    thickness
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed box of side `s` (12 triangles), its normals pointing out of the corners.
    fn cube(s: f32) -> (Vec<Vec3>, Vec<Vec3>, Vec<u32>) {
        let p: Vec<Vec3> =
            (0..8).map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, (i >> 2) as f32) * s).collect();
        let centre = Vec3::splat(s / 2.0);
        let n = p.iter().map(|&v| v - centre).collect();
        let faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]];
        let i = faces.iter().flat_map(|[a, b, c, d]| [*a, *b, *c, *a, *c, *d]).collect();
        (p, n, i)
    }

    #[test]
    fn the_memo_gives_vertex_thickness_and_computes_a_mesh_once() {
        let (p, n, i) = cube(2.0);
        let first = vertex_thickness_memo(&p, &n, &i);
        assert_eq!(&first[..], &vertex_thickness(&p, &n, &i)[..]);
        // A corner's ray along the inward diagonal leaves through the opposite corner.
        assert!((first[0] - 2.0 * 3f32.sqrt()).abs() < 1e-3, "{first:?}");
        assert!(Arc::ptr_eq(&first, &vertex_thickness_memo(&p, &n, &i)), "asked again, computed again");
        // Another mesh is not given the first one's values: neither a scaled box, nor one whose
        // normals or triangles alone differ.
        let (q, m, j) = cube(3.0);
        assert!((vertex_thickness_memo(&q, &m, &j)[0] - 3.0 * 3f32.sqrt()).abs() < 1e-3);
        let flat: Vec<Vec3> = n.iter().map(|_| Vec3::Y).collect();
        assert_eq!(&vertex_thickness_memo(&p, &flat, &i)[..], &vertex_thickness(&p, &flat, &i)[..]);
        assert!(!Arc::ptr_eq(&first, &vertex_thickness_memo(&p, &flat, &i)));
        let half = &i[..18];
        assert_eq!(&vertex_thickness_memo(&p, &n, half)[..], &vertex_thickness(&p, &n, half)[..]);
        assert!(!Arc::ptr_eq(&first, &vertex_thickness_memo(&p, &n, half)));
    }

    #[test]
    fn the_memo_forgets_the_oldest_mesh_past_its_size() {
        let meshes: Vec<_> = (0..3).map(|k| cube(1.0 + k as f32)).collect();
        let mut memo = Memo::default();
        for (k, (p, n, i)) in meshes.iter().enumerate() {
            memo.keep(p, n, i, &vec![k as f32; p.len()].into(), 2);
        }
        let found = |m: &Memo, k: usize| m.find(&meshes[k].0, &meshes[k].1, &meshes[k].2).map(|t| t[0]);
        assert_eq!([found(&memo, 0), found(&memo, 1), found(&memo, 2)], [None, Some(1.0), Some(2.0)]);
        // A mesh kept again is not kept twice, and does not push another out.
        memo.keep(&meshes[2].0, &meshes[2].1, &meshes[2].2, &vec![9.0; 8].into(), 2);
        assert_eq!([found(&memo, 1), found(&memo, 2)], [Some(1.0), Some(2.0)]);
    }
}
