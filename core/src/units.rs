//! Numbers as the formats write them: the size limits that catch a unit mistake, the height
//! below which an object is a floor covering, angles in degrees, and numbers as people read them.
//! The lowest module of the crate: rooms, scenes and geometry all build on it.

/// Largest room side accepted, in cm (100 m). Anything larger is almost certainly a unit mistake.
pub const MAX_ROOM_SIDE_CM: f64 = 10_000.0;

/// Objects this tall or lower (cm) are floor coverings (rugs, mats): they may lie under furniture.
pub const FLAT_HEIGHT_CM: f64 = 3.0;

/// The smallest room side taken: anything shorter was surely written in metres.
pub const MIN_ROOM_SIDE_CM: f64 = 50.0;

/// A number as people write it: `1e308`, not 309 digits.
pub fn show_number(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-3..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// Normalises an angle in degrees to `[0, 360)`.
pub fn normalize_degrees(deg: f64) -> f64 {
    let r = deg.rem_euclid(360.0);
    if r >= 360.0 - 1e-9 { 0.0 } else { r }
}
