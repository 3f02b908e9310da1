//! Numbers in field-error messages: plain decimals for ordinary magnitudes, exponent form
//! for tiny or huge ones, and four significant digits where a value was computed.

/// `value` to four significant digits, printed as [`num`] does.
pub(crate) fn sig(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || !value.is_finite() || !(1e-4..1e9).contains(&magnitude) {
        return format!("{value:.3e}");
    }
    // Scale by an exact power of ten (multiply or divide by 10^k, k >= 0) so the rounding
    // leaves no binary residue such as 24969.999999999996.
    let shift = 3 - magnitude.log10().floor() as i32;
    let scale = 10f64.powi(shift.abs());
    let rounded = if shift >= 0 {
        (value * scale).round() / scale
    } else {
        (value / scale).round() * scale
    };
    format!("{rounded}")
}

/// Plain decimals for ordinary magnitudes, exponent form for tiny or huge ones
/// (Rust's `{}` would print 1e-15 as 0.000000000000001).
pub(crate) fn num(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || !value.is_finite() || (1e-4..1e9).contains(&magnitude) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_significant_digits() {
        assert_eq!(sig(24_972.295), "24970");
        assert_eq!(sig(0.024_73), "0.02473");
        assert_eq!(sig(75.240_55), "75.24");
        assert_eq!(sig(6.992e-296), "6.992e-296");
    }

    #[test]
    fn small_and_large_numbers_print_in_exponent_form() {
        assert_eq!(num(1e-15), "1e-15");
        assert_eq!(num(-5.0), "-5");
        assert_eq!(num(0.45), "0.45");
        assert_eq!(num(2e12), "2e12");
    }
}
