//! Exact geometric optics in `f64`: mirror reflection, Snell refraction and the unpolarised
//! dielectric Fresnel reflectance.
//!
//! Conventions: `d` is the unit propagation direction, `n` a unit normal on the side the
//! ray comes from (`d · n < 0`); `eta = n_i / n_t` is the ratio of the refractive index of
//! the medium the ray leaves to the one it enters.

use glam::DVec3;

/// Mirror reflection of `d` about the plane with normal `n` (either orientation).
#[inline]
pub fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

/// Snell refraction: `n_i sin θ_i = n_t sin θ_t`. `n` must face the incoming ray
/// (`d · n < 0`). Returns `None` on total internal reflection (`sin θ_t > 1`).
#[inline]
pub fn refract(d: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -d.dot(n);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    if k < 0.0 {
        return None;
    }
    Some((eta * d + (eta * cos_i - k.sqrt()) * n).normalize())
}

/// Critical angle (radians) for light going from index `n_i` into `n_t < n_i`; `None`
/// when `n_t >= n_i` (no total internal reflection possible).
pub fn critical_angle(n_i: f64, n_t: f64) -> Option<f64> {
    (n_t < n_i).then(|| (n_t / n_i).asin())
}

/// Exact unpolarised Fresnel reflectance of a smooth dielectric interface, the mean of
/// the s- and p-polarised reflectances:
///
/// `r_s = (n_i cos θ_i − n_t cos θ_t) / (n_i cos θ_i + n_t cos θ_t)`,
/// `r_p = (n_t cos θ_i − n_i cos θ_t) / (n_t cos θ_i + n_i cos θ_t)`,
/// `F = (r_s² + r_p²) / 2`; `F = 1` under total internal reflection.
/// `cos_i` is the cosine of the angle of incidence (its absolute value is used). The
/// transmitted power fraction is `1 − F` (photon power, not radiance, so no `η²` factor).
pub fn fresnel_dielectric(cos_i: f64, n_i: f64, n_t: f64) -> f64 {
    let cos_i = cos_i.abs().min(1.0);
    let sin_i2 = (1.0 - cos_i * cos_i).max(0.0);
    let sin_t2 = (n_i / n_t) * (n_i / n_t) * sin_i2;
    if sin_t2 >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    let rs = (n_i * cos_i - n_t * cos_t) / (n_i * cos_i + n_t * cos_t);
    let rp = (n_t * cos_i - n_i * cos_t) / (n_t * cos_i + n_i * cos_t);
    (0.5 * (rs * rs + rp * rp)).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir_at(theta: f64) -> DVec3 {
        // Incidence angle `theta` from the -y axis, in the xy plane, travelling down.
        DVec3::new(theta.sin(), -theta.cos(), 0.0)
    }

    #[test]
    fn snell_sine_ratio() {
        let n = DVec3::Y;
        for &(n1, n2) in &[(1.0, 1.5), (1.0, 2.4), (1.33, 1.0), (1.5, 1.2)] {
            for k in 0..20 {
                let theta = k as f64 * 0.07;
                let d = dir_at(theta);
                let Some(t) = refract(d, n, n1 / n2) else {
                    assert!(n1 * theta.sin() > n2, "unexpected TIR {n1} {n2} {theta}");
                    continue;
                };
                assert!((t.length() - 1.0).abs() < 1e-12);
                assert!(t.y < 0.0, "transmitted ray keeps going down");
                let sin_t = (t.x * t.x + t.z * t.z).sqrt();
                assert!((n1 * theta.sin() - n2 * sin_t).abs() < 1e-12);
                // Same plane of incidence, same side.
                assert!(t.z.abs() < 1e-12 && t.x * d.x >= 0.0);
            }
        }
        // Normal incidence goes straight through.
        let t = refract(-DVec3::Y, DVec3::Y, 1.0 / 1.5).unwrap();
        assert!((t - -DVec3::Y).length() < 1e-15);
    }

    #[test]
    fn tir_threshold_at_critical_angle() {
        let (n1, n2) = (1.5, 1.0);
        // Glass to air: 41.81 degrees, the textbook value (asin(1 / 1.5) = 0.72972765622697 rad).
        let crit = critical_angle(n1, n2).unwrap();
        assert!((crit - 0.72972765622697).abs() < 1e-13, "{crit}");
        assert!(critical_angle(1.0, 1.5).is_none());
        // Equal indices are no interface: no critical angle (not one of 90 degrees).
        assert!(critical_angle(1.5, 1.5).is_none());
        assert!(refract(dir_at(crit - 1e-6), DVec3::Y, n1 / n2).is_some());
        assert!(refract(dir_at(crit + 1e-6), DVec3::Y, n1 / n2).is_none());
        assert_eq!(fresnel_dielectric((crit + 1e-6).cos(), n1, n2), 1.0);
        assert!(fresnel_dielectric((crit - 1e-3).cos(), n1, n2) < 1.0);
        // Entering a denser medium never reflects totally.
        assert!(refract(dir_at(1.57), DVec3::Y, n2 / n1).is_some());
    }

    #[test]
    fn fresnel_normal_incidence_and_grazing() {
        for &n in &[1.33, 1.5, 2.42] {
            let expect = ((n - 1.0) / (n + 1.0)) * ((n - 1.0) / (n + 1.0));
            assert!((fresnel_dielectric(1.0, 1.0, n) - expect).abs() < 1e-14);
            assert!((fresnel_dielectric(1.0, n, 1.0) - expect).abs() < 1e-14);
            // -> 1 at grazing incidence, monotone on the way for external reflection.
            assert!(fresnel_dielectric(1e-6, 1.0, n) > 0.9999);
            let mut prev = 0.0;
            for k in (1..=100).rev() {
                let f = fresnel_dielectric(k as f64 / 100.0, 1.0, n);
                assert!(f >= prev - 1e-12, "non-monotone at cos {}", k);
                prev = f;
            }
        }
        assert!((fresnel_dielectric(1.0, 1.0, 1.5) - 0.04).abs() < 1e-12);
    }

    #[test]
    fn fresnel_energy_conservation_and_reciprocity() {
        // R + T = 1 with T computed independently from the transmission amplitudes:
        // T = (n_t cos_t)/(n_i cos_i) * (t_s² + t_p²)/2.
        for &(n1, n2) in &[(1.0, 1.5), (1.5, 1.0), (1.0, 1.33)] {
            for k in 0..90 {
                let ti = (k as f64).to_radians();
                let (ci, si) = (ti.cos(), ti.sin());
                let st = n1 / n2 * si;
                if st >= 1.0 {
                    continue;
                }
                let ct = (1.0 - st * st).sqrt();
                let ts = 2.0 * n1 * ci / (n1 * ci + n2 * ct);
                let tp = 2.0 * n1 * ci / (n2 * ci + n1 * ct);
                let t = (n2 * ct) / (n1 * ci) * 0.5 * (ts * ts + tp * tp);
                let r = fresnel_dielectric(ci, n1, n2);
                assert!((r + t - 1.0).abs() < 1e-12, "R+T={} at {k} deg", r + t);
                // Reciprocity: same reflectance from the other side at the refracted angle.
                assert!((fresnel_dielectric(ct, n2, n1) - r).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn reflection_is_a_mirror() {
        let d = DVec3::new(0.3, -0.8, 0.1).normalize();
        let r = reflect(d, DVec3::Y);
        assert!((r - DVec3::new(d.x, -d.y, d.z)).length() < 1e-15);
        assert!((reflect(d, -DVec3::Y) - r).length() < 1e-15);
    }

    #[test]
    fn equal_indices_pass_the_ray_on_unbent_even_at_grazing_incidence() {
        // eta = 1 is no interface: every ray goes straight on. At grazing incidence (d · n = 0)
        // Snell's k = 1 - eta²(1 - cos²θ) is exactly 0, the boundary of total internal
        // reflection: the ray is transmitted (sin θ_t = 1), not reflected.
        let n = DVec3::Y;
        for d in [DVec3::X, dir_at(0.3), dir_at(1.2), DVec3::new(0.6, 0.0, -0.8)] {
            let t = refract(d, n, 1.0).unwrap_or_else(|| panic!("{d}: reflected totally at eta = 1"));
            assert!((t - d).length() < 1e-12, "{d} -> {t}");
        }
    }
}
