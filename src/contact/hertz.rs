//! Hertz's analytic solution for a sphere on a flat (Johnson, Contact Mechanics, sec. 4.2):
//! the reference every grid and tolerance is measured against.

use std::f64::consts::PI;

/// The Hertz contact of a sphere of radius `R` pressed with load `F` on a flat, for a
/// reduced modulus `E*`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    /// Sphere radius, m.
    pub radius_m: f64,
    /// Load, N.
    pub load_n: f64,
    /// Reduced modulus E*, Pa.
    pub reduced_modulus_pa: f64,
}

impl Hertz {
    /// Contact radius `a = (3 F R / (4 E*))^(1/3)`, m.
    pub fn contact_radius_m(&self) -> f64 {
        (3.0 * self.load_n * self.radius_m / (4.0 * self.reduced_modulus_pa)).cbrt()
    }

    /// Peak pressure `p0 = 3 F / (2 pi a^2)`, Pa.
    pub fn peak_pressure_pa(&self) -> f64 {
        let a = self.contact_radius_m();
        3.0 * self.load_n / (2.0 * PI * a * a)
    }

    /// Contact area `pi a^2`, m^2.
    pub fn contact_area_m2(&self) -> f64 {
        let a = self.contact_radius_m();
        PI * a * a
    }

    /// Approach `delta = a^2 / R`, m.
    pub fn approach_m(&self) -> f64 {
        let a = self.contact_radius_m();
        a * a / self.radius_m
    }

    /// Pressure at distance `r` from the centre, `p0 sqrt(1 - r^2 / a^2)` inside, 0 outside.
    pub fn pressure_pa(&self, r: f64) -> f64 {
        let a = self.contact_radius_m();
        if r >= a {
            0.0
        } else {
            self.peak_pressure_pa() * (1.0 - (r / a).powi(2)).sqrt()
        }
    }

    /// The paraboloid separation `h = r^2 / (2 R)` of the sphere near its apex, m. Hertz's
    /// theory uses this approximation; the exact sphere differs by `r^4 / (8 R^3)`, below
    /// 4e-4 of `h` over the contact here.
    pub fn separation_m(&self, x: f64, y: f64) -> f64 {
        (x * x + y * y) / (2.0 * self.radius_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_values() {
        // Paper Section 2.3: p0 = 1221 MPa; Section 5.1: Hertzian area 6e-3 mm^2 (6.1e-3 to
        // two digits). E* = 130.17 GPa from the moduli in GPa (the paper prints MPa, a slip).
        let hertz = Hertz {
            radius_m: 3e-3,
            load_n: 5.0,
            reduced_modulus_pa: 130.17e9,
        };
        assert!((hertz.peak_pressure_pa() / 1e6 - 1221.0).abs() < 1.0);
        assert!((hertz.contact_area_m2() * 1e6 - 6.1e-3).abs() < 0.05e-3);
        // Load balance: int p dA = 2 pi a^2 p0 / 3 = F.
        let a = hertz.contact_radius_m();
        let carried = 2.0 * PI * a * a * hertz.peak_pressure_pa() / 3.0;
        assert!((carried / hertz.load_n - 1.0).abs() < 1e-14);
    }
}
