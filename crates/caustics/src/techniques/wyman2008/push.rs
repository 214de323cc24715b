//! Push constants of Wyman 2008's passes: building the photon hierarchy (Sec. 3.2), its
//! traversal (Sec. 3.3) and the `splats` dump. Each is the twin of a GLSL
//! `layout(push_constant)` block of the same name and members (`crate::gpu::push`); the tests
//! compare them through the SPIR-V of every shader that declares one.

use vkcore::push_constants;

push_constants! {
    /// Building one level of the photon hierarchy (`wyman2008/build.comp`).
    pub struct BuildConstants {
        /// k >= 1.
        pub level: u32,
        pub light: u32,
        /// The photon buffer side N.
        pub photon_side: u32,
    }
}

push_constants! {
    /// One step of the hierarchical traversal (`wyman2008/traverse.glsl`).
    pub struct TraverseConstants {
        pub light: u32,
        /// 1 when convergence is tested at this level.
        pub cluster: u32,
        /// The photon buffer side N.
        pub photon_side: u32,
    }
}

push_constants! {
    /// The `splats` dump (`wyman2008/splat_footprints.comp`).
    pub struct FootprintConstants {
        /// Entries in the traversal's final list.
        pub entries: u32,
        pub light: u32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::push::check;
    use vkcore::{check_push_constants, ShaderCompiler};

    #[test]
    fn build_constants() {
        check::<BuildConstants>(&[("wyman2008/build.comp", &[])]);
    }

    #[test]
    fn traverse_constants() {
        check::<TraverseConstants>(&[("wyman2008/traverse.geom", &[]), ("wyman2008/traverse.comp", &[])]);
    }

    #[test]
    fn footprint_constants() {
        check::<FootprintConstants>(&[("wyman2008/splat_footprints.comp", &[])]);
    }

    /// The reflection the checks rely on tells a renamed or reordered member apart.
    #[test]
    fn a_renamed_or_reordered_member_fails() {
        mod renamed {
            vkcore::push_constants! {
                pub struct FootprintConstants { pub entries: u32, pub lamp: u32 }
            }
        }
        mod reordered {
            vkcore::push_constants! {
                pub struct FootprintConstants { pub light: u32, pub entries: u32 }
            }
        }
        let sh = ShaderCompiler::new(&crate::render::shader_root()).unwrap();
        let spirv = sh.compile("wyman2008/splat_footprints.comp", &[]).unwrap();
        assert!(check_push_constants::<FootprintConstants>(&spirv).is_ok());
        let renamed = check_push_constants::<renamed::FootprintConstants>(&spirv).unwrap_err();
        assert!(renamed.contains("lamp"), "{renamed}");
        assert!(check_push_constants::<reordered::FootprintConstants>(&spirv).is_err());
    }
}
