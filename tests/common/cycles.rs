//! Cycles' shipped tables (`tests/data/engines/cycles/shader.tables`, Apache-2.0; see the
//! README there), read by the tests that compare with them.

const SHADER_TABLES: &str = include_str!("../data/engines/cycles/shader.tables");

/// The values of Cycles' `table_NAME[…]`, in its printed order (e.g. index z·256 + y·16 + x
/// for glass_E).
pub fn table(name: &str) -> Vec<f64> {
    let start = SHADER_TABLES
        .find(&format!("table_{name}["))
        .unwrap_or_else(|| panic!("{name} in shader.tables"));
    let body = &SHADER_TABLES[start..];
    let body = &body[body.find('{').unwrap() + 1..body.find('}').unwrap()];
    body.split(',')
        .map(|s| s.trim().trim_end_matches('f').parse::<f64>().unwrap())
        .collect()
}
