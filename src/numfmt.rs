//! Numbers in messages: short and exact enough to act on. `{}` prints an f64 with every
//! digit its shortest round trip needs (`1e300` as 301 digits, `1.7500000000000002e-9`);
//! an error message needs the value a user typed or can compare, not its last bit.

/// `x` with at most 6 significant digits: plain for 1e-4 ≤ |x| < 1e6, else scientific
/// (`1.75e-9`, `1e300`, `0.25`, `inf`, `NaN`).
pub fn num(x: f64) -> String {
    significant(x, 6, 1e-4..1e6)
}

/// `x` to 4 significant digits, as charts label a value (`21.79`, `0.9806`, `-4.936e-9`):
/// within half a unit of the 4th digit (5e-4 relative); plain for 1e-3 ≤ |x| < 1e4.
pub fn sig4(x: f64) -> String {
    significant(x, 4, 1e-3..1e4)
}

/// `x` rounded to `digits` significant digits, trailing zeros dropped: plain when |x| is in
/// `plain`, else scientific.
fn significant(x: f64, digits: usize, plain: std::ops::Range<f64>) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".into();
    }
    let trim = |s: &str| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    let a = x.abs();
    if plain.contains(&a) {
        let decimals = (digits as i32 - 1 - a.log10().floor() as i32).max(0) as usize;
        return trim(&format!("{x:.decimals$}"));
    }
    let s = format!("{x:.*e}", digits - 1);
    let (m, e) = s.split_once('e').expect("scientific");
    format!("{}e{e}", trim(m))
}

/// `x` with two significant digits, as the docs quote figures: plain for 0.01 ≤ |x| < 1000
/// (`0.93`, `0.021`, `5.3`, `0.30`), else scientific (`9.7e-7`, `1.4e-3`).
pub fn fig(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if (0.01..1000.0).contains(&a) {
        // (rounding may carry into a new digit: 0.0996 -> 0.100; 2 digits are kept)
        let decimals = (1 - a.log10().floor() as i32).max(0) as usize;
        return format!("{x:.decimals$}");
    }
    format!("{x:.1e}")
}

/// `x` with at most 3 significant digits, for coordinates in a short text: plain for
/// 1e-3 ≤ |x| < 1e4 (`0.0317`, `0.35`, `99.5`), else scientific (`1e-4`, `2.5e-5`).
pub fn short(x: f64) -> String {
    significant(x, 3, 1e-3..1e4)
}

/// A value near 1 with the digits that tell it from 1: `1 + 2e-8`, `1 - 3.5e-6`; other
/// values as [`num`].
pub fn near_one(x: f64) -> String {
    let d = x - 1.0;
    if d != 0.0 && d.abs() < 1e-4 {
        format!("1 {} {}", if d > 0.0 { "+" } else { "-" }, num(d.abs()))
    } else {
        num(x)
    }
}

/// Seconds for people: `850 ms`, `12.3 s`, `4.5 min`, `2.1 h`.
pub fn human_seconds(s: f64) -> String {
    if s < 1.0 {
        format!("{:.0} ms", s * 1e3)
    } else if s < 120.0 {
        format!("{s:.1} s")
    } else if s < 7200.0 {
        format!("{:.1} min", s / 60.0)
    } else {
        format!("{:.1} h", s / 3600.0)
    }
}

/// `bytes` for people: `1.5 GiB`, `12.0 MiB`, `512 bytes`.
pub fn human_bytes(bytes: u64) -> String {
    const UNITS: [(&str, u64); 3] = [("GiB", 1 << 30), ("MiB", 1 << 20), ("KiB", 1 << 10)];
    for (name, size) in UNITS {
        if bytes >= size {
            return format!("{:.1} {name}", bytes as f64 / size as f64);
        }
    }
    format!("{bytes} bytes")
}

#[cfg(test)]
mod tests {
    use super::{fig, near_one, num, short, sig4};

    #[test]
    fn figures_and_values_near_one() {
        assert_eq!(fig(0.93), "0.93");
        assert_eq!(fig(0.0214), "0.021");
        assert_eq!(fig(9.74e-7), "9.7e-7");
        assert_eq!(fig(0.0996), "0.100");
        assert_eq!(fig(0.2990), "0.30");
        assert_eq!(fig(0.00996), "1.0e-2");
        assert_eq!(fig(-2.5e-3), "-2.5e-3");
        assert_eq!(fig(173.4), "173");
        assert_eq!(near_one(1.00000002), "1 + 2e-8");
        assert_eq!(short(0.0316941), "0.0317");
        assert_eq!(short(0.35), "0.35");
        assert_eq!(short(1e-4), "1e-4");
        assert_eq!(short(99.5025), "99.5");
        assert_eq!(near_one(0.999), "0.999");
        assert_eq!(near_one(1.0), "1");
    }

    #[test]
    fn short_forms() {
        assert_eq!(num(1.7500000000000002e-9), "1.75e-9");
        assert_eq!(num(1e300), "1e300");
        assert_eq!(num(0.25), "0.25");
        assert_eq!(num(-3.0), "-3");
        assert_eq!(num(123456.7), "123457");
        assert_eq!(num(1e6), "1e6");
        assert_eq!(num(0.1 + 0.2), "0.3");
        assert_eq!(num(5e-324), "4.94066e-324");
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(num(f64::INFINITY), "inf");
        assert_eq!(num(0.0), "0");
        assert_eq!(num(1e-4), "0.0001");
    }

    #[test]
    fn four_digits() {
        assert_eq!(sig4(21.786140), "21.79");
        assert_eq!(sig4(0.98061), "0.9806");
        assert_eq!(sig4(0.99999994), "1");
        assert_eq!(sig4(-4.935667e-9), "-4.936e-9");
        assert_eq!(sig4(12346.0), "1.235e4");
        assert_eq!(sig4(0.0), "0");
    }
}
