//! The settings only `pool-convolution` has (Trendall & Stewart 2000), as the scene's
//! `[caustics]`, the bench configs and the command line name them, and the technique's dumps (a
//! leaf module: the scene description reads it).

use super::super::settings::{Bad, CausticSettings};
use super::super::value_enum::value_enum;
use crate::dump::{layer, layer_when, Dump, Format, LayerDecl, Space};

/// The paper, as tables and `--help` cite it.
pub const PAPER: &str = "Trendall & Stewart 2000, pool caustics as convolutions";

/// The buffers `pool-convolution` has (`--dump` names): the height field, each pass's function,
/// the convolutions, and the pool-bottom receiver map.
pub static DUMPS: &[&Dump] = &[
    &HEIGHT_FIELD,
    &PASS1_NORMALS,
    &PASS2_GAMMA_N,
    &PASS3_TRANSMITTED,
    &PASS4_DIRECTION,
    &PASS5_INTEGRAND,
    &PASS6_CONVOLUTIONS,
    &RECEIVER,
];
pub static HEIGHT_FIELD: Dump =
    Dump::new("height_field", module_path!(), Space::Pool, Format::Image, &pass_layers(&["h"]));
pub static PASS1_NORMALS: Dump =
    Dump::new("pass1_normals", module_path!(), Space::Pool, Format::Image, &pass_layers(XYZ));
pub static PASS2_GAMMA_N: Dump =
    Dump::new("pass2_gamma_n", module_path!(), Space::Pool, Format::Image, &pass_layers(XYZ));
pub static PASS3_TRANSMITTED: Dump =
    Dump::new("pass3_transmitted", module_path!(), Space::Pool, Format::Image, &pass_layers(&["value"]));
pub static PASS4_DIRECTION: Dump =
    Dump::new("pass4_direction", module_path!(), Space::Pool, Format::Image, &pass_layers(XYZ));
pub static PASS5_INTEGRAND: Dump =
    Dump::new("pass5_integrand", module_path!(), Space::Pool, Format::Image, &pass_layers(XYZ));
pub static PASS6_CONVOLUTIONS: Dump = Dump::new(
    "pass6_convolutions",
    module_path!(),
    Space::Pool,
    Format::Image,
    &[
        layer("", CONVOLUTIONS),
        layer("flat", CONVOLUTIONS),
        layer_when("adjusted", CONVOLUTIONS, "with `--precision unorm8`"),
    ],
);
/// The pool bottom's receiver map (not the eye render's `receiver`: another declaration).
pub static RECEIVER: Dump = Dump::new(
    "receiver",
    module_path!(),
    Space::Pool,
    Format::Image,
    &[layer("", &["R", "G", "B", "E0"]), layer("irradiance", &["R", "G", "B"])],
);

/// The channels of Pass 1, 2, 4 and 5's dumps: a vector in world axes or the expansion basis.
pub const XYZ: &[&str] = &["X", "Y", "Z"];
/// Pass 6's channels: the three convolutions and their sum (Eq. 2).
pub const CONVOLUTIONS: &[&str] = &["E_x", "E_y", "E_z", "E"];

/// A pass's layers: its physical values, and on the 8-bit path also the stored ones (Sec. 3.2).
const fn pass_layers(channels: &'static [&'static str]) -> [LayerDecl; 2] {
    [layer("", channels), layer_when("adjusted", channels, "with `--precision unorm8`")]
}

/// The default side of the Pass 6 kernels (the paper's 7 x 7).
pub const DEFAULT_KERNEL: u32 = 7;
/// The widest kernel side accepted.
pub const MAX_KERNEL: u32 = 63;

value_enum! {
    /// The arithmetic of passes 1-6 (`caustics.precision`, `--precision`).
    pub enum Precision {
        /// The paper's hardware: fragment passes into 8-bit UNORM targets, scale-and-bias
        /// ("adjusted") arithmetic and 8-bit lookup tables (Sec. 3.2, 4.1-4.2).
        Unorm8 = "unorm8",
        /// The same fragment passes into 32-bit float targets, without lookup tables.
        Float = "float",
        /// The paper's software implementation: the same passes on the CPU in f64.
        F64 = "f64",
    }
}

/// The range check of technique `pool-convolution`'s own key (`CausticSettings::validate` calls
/// it): the Pass 6 kernel's taps per side.
pub fn validate_ranges(s: &CausticSettings, bad: Bad) -> anyhow::Result<()> {
    if !(3..=MAX_KERNEL).contains(&s.kernel) || s.kernel.is_multiple_of(2) {
        let why = format!("must be an odd number between 3 and {MAX_KERNEL} (taps per side), got {}", s.kernel);
        bad("kernel", why)?;
    }
    Ok(())
}
