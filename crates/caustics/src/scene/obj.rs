//! Wavefront OBJ loading through tobj: all groups merged into one triangle mesh, the file's
//! normals kept when every vertex has a valid one, smooth area-weighted normals otherwise.

use super::mesh::Mesh;
use glam::Vec3;
use std::path::Path;

/// Loads `path` in object space. The error is a sentence without the file name (the caller
/// adds the scene file, key and OBJ path).
pub fn load_obj(path: &Path) -> Result<Mesh, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read: {e}"))?;
    load_obj_bytes(&bytes)
}

/// [`load_obj`] of a file already read (the scene loader hashes the same bytes,
/// [`super::models`]). Materials are not read: the scene gives them.
pub fn load_obj_bytes(bytes: &[u8]) -> Result<Mesh, String> {
    let options = tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true };
    let (models, _materials) =
        tobj::load_obj_buf(&mut std::io::Cursor::new(bytes), &options, |_| Err(tobj::LoadError::OpenFileFailed))
            .map_err(|e| format!("malformed OBJ: {e}"))?;
    let mut mesh = Mesh::default();
    let mut file_normals_ok = true;
    for model in &models {
        let m = &model.mesh;
        if m.positions.len() % 3 != 0 || m.indices.len() % 3 != 0 {
            return Err(format!("malformed OBJ: group `{}` has truncated data", model.name));
        }
        let vertex_count = m.positions.len() / 3;
        let positions: Vec<Vec3> = m.positions.chunks_exact(3).map(|p| Vec3::new(p[0], p[1], p[2])).collect();
        if let Some(p) = positions.iter().find(|p| !p.is_finite()) {
            return Err(format!("malformed OBJ: non-finite vertex position {p}"));
        }
        if let Some(&i) = m.indices.iter().find(|&&i| i as usize >= vertex_count) {
            return Err(format!(
                "malformed OBJ: a face references vertex {} but group `{}` has {vertex_count}",
                i as u64 + 1,
                model.name
            ));
        }
        let normals: Vec<Vec3> = m.normals.chunks_exact(3).map(|n| Vec3::new(n[0], n[1], n[2])).collect();
        if normals.len() != vertex_count || normals.iter().any(|n| !n.is_finite() || n.length_squared() < 1e-20) {
            file_normals_ok = false;
        }
        let part = Mesh {
            positions,
            normals: if file_normals_ok { normals.iter().map(|n| n.normalize()).collect() } else { Vec::new() },
            indices: m.indices.clone(),
        };
        mesh.append(&part);
    }
    if mesh.triangle_count() == 0 {
        return Err("malformed OBJ: it contains no triangles".to_string());
    }
    if !file_normals_ok || mesh.normals.len() != mesh.positions.len() {
        mesh.compute_smooth_normals();
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write_temp(name: &str, text: &str) -> crate::scratch::ScratchDir {
        let p = crate::scratch::ScratchDir::new("causticlab-obj", "load").within(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn tetrahedron_without_normals_gets_smooth_ones() {
        let p = write_temp("tet.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
        let m = load_obj(&p).unwrap();
        assert_eq!(m.triangle_count(), 4);
        assert!((m.signed_volume() - 1.0 / 6.0).abs() < 1e-6);
        // Vertex 0 sees three faces of area 1/2 with normals -x, -y, -z.
        assert!((m.normals[0] - Vec3::splat(-1.0).normalize()).length() < 1e-6);
    }

    #[test]
    fn file_normals_are_kept() {
        let p = write_temp("n.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nvn 0 2 0\nf 1//1 3//1 2//1\n");
        let m = load_obj(&p).unwrap();
        assert_eq!(m.normals, vec![Vec3::Y; 3]);
    }

    #[test]
    fn malformed_files_are_errors() {
        for (name, text) in [
            ("oob.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n"),
            ("empty.obj", "# nothing\n"),
            ("junk.obj", "v 0 zero 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        ] {
            let e = load_obj(&write_temp(name, text)).unwrap_err();
            assert!(e.contains("malformed OBJ"), "{name}: {e}");
        }
    }
}
