//! Refraction at the air-water boundary (Sec. 4): Snell's law as Eq. 1, L_t = (n_i/n_t) L_i +
//! Gamma N with Gamma = (n_i/n_t) cos(theta_i) - cos(theta_t), and the Fresnel transmission
//! coefficient T(theta_i), averaged over polarisations, in the paper's form. Both are functions
//! of cos(theta_i) alone (Sec. 4.1), which is what lets the hardware look them up in tables.

use glam::DVec3;

/// The boundary between air (n_i) and water (n_t), n_i < n_t (no total internal reflection).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interface {
    pub n_i: f64,
    pub n_t: f64,
}

impl Interface {
    /// n_i / n_t.
    pub fn eta(&self) -> f64 {
        self.n_i / self.n_t
    }

    /// cos(theta_t) from cos(theta_i) (Snell's law).
    pub fn cos_transmitted(&self, cos_i: f64) -> f64 {
        let e = self.eta();
        (1.0 - e * e * (1.0 - cos_i * cos_i)).max(0.0).sqrt()
    }

    /// Gamma of Eq. 1.
    pub fn gamma(&self, cos_i: f64) -> f64 {
        self.eta() * cos_i - self.cos_transmitted(cos_i)
    }

    /// T(theta_i) of Sec. 4: the ratio of transmitted exitance to incident irradiance,
    /// 2 (n_t cos t)/(n_i cos i) ([n_i cos i/(n_i cos i + n_t cos t)]^2 + [n_i cos i/(n_t cos i + n_i cos t)]^2).
    pub fn transmittance(&self, cos_i: f64) -> f64 {
        if cos_i <= 0.0 {
            return 0.0;
        }
        let (ni, nt) = (self.n_i, self.n_t);
        let ct = self.cos_transmitted(cos_i);
        let s = ni * cos_i / (ni * cos_i + nt * ct);
        let p = ni * cos_i / (nt * cos_i + ni * ct);
        2.0 * (nt * ct) / (ni * cos_i) * (s * s + p * p)
    }

    /// Eq. 1: the transmitted direction L_t of light travelling along `l_i` through a surface of
    /// normal `n` (pointing into the air), and cos(theta_i) = -L_i . N.
    pub fn transmitted(&self, l_i: DVec3, n: DVec3) -> (DVec3, f64) {
        let cos_i = -l_i.dot(n);
        (self.eta() * l_i + self.gamma(cos_i) * n, cos_i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const WATER: Interface = Interface { n_i: 1.0, n_t: 1.333 };

    /// The textbook form: 1 - (R_s + R_p) / 2 with the Fresnel amplitude ratios.
    fn one_minus_reflectance(n1: f64, n2: f64, ci: f64) -> f64 {
        let ct = (1.0 - (n1 / n2).powi(2) * (1.0 - ci * ci)).sqrt();
        let rs = ((n1 * ci - n2 * ct) / (n1 * ci + n2 * ct)).powi(2);
        let rp = ((n2 * ci - n1 * ct) / (n2 * ci + n1 * ct)).powi(2);
        1.0 - 0.5 * (rs + rp)
    }

    #[test]
    fn transmittance_is_one_minus_the_mean_reflectance() {
        for deg in [0.0f64, 10.0, 30.0, 45.0, 60.0, 75.0, 89.0] {
            let ci = deg.to_radians().cos();
            let t = WATER.transmittance(ci);
            assert!((t - one_minus_reflectance(1.0, 1.333, ci)).abs() < 1e-12, "{deg}: {t}");
        }
        // Normal incidence: 1 - ((n - 1) / (n + 1))^2.
        assert!((WATER.transmittance(1.0) - (1.0 - (0.333f64 / 2.333).powi(2))).abs() < 1e-12);
    }

    #[test]
    fn transmitted_direction_obeys_snell() {
        let n = DVec3::Y;
        for deg in [0.0f64, 20.0, 50.0, 80.0] {
            let a = deg.to_radians();
            let l = DVec3::new(a.sin(), -a.cos(), 0.0);
            let (t, ci) = WATER.transmitted(l, n);
            assert!((t.length() - 1.0).abs() < 1e-12);
            assert!((ci - a.cos()).abs() < 1e-12);
            // n_i sin(i) = n_t sin(t), in the plane of incidence, travelling down.
            assert!((t.x * 1.333 - a.sin()).abs() < 1e-12 && t.y < 0.0 && t.z == 0.0);
        }
    }
}
