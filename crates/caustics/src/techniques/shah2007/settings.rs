//! What Shah et al.'s techniques declare: the paper and the features the vertex-photon pass
//! needs (a leaf module: the technique enum reads it).

use vkcore::Feature;

/// The paper, as tables and `--help` cite it.
pub const PAPER: &str = "Shah, Konttinen & Pattanaik 2007, caustics mapping";

/// What the vertex-photon pass needs: it writes the photon buffer from the vertex stage.
pub const VERTEX_PHOTON_FEATURES: &[Feature] =
    &[Feature::ShaderOutputLayer, Feature::LargePoints, Feature::VertexPipelineStoresAndAtomics];
