//! Formations: group layouts with counts ("two rows of five facing the screen", "six chairs in a
//! semicircle facing the piano", "two pods of four desks"), computed exactly.
//!
//! Every function here is pure and deterministic: it takes the focus or anchor (a [`Footprint`] or
//! a point), the members' [`Size`], counts and gaps, and returns world [`Pose`]s in a documented
//! order. Angles are free (a seat turned to a focus keeps its exact angle; nothing snaps to 90°).
//! Conventions are those of docs/formats.md: cm, x right, y up, rotation in degrees clockwise with
//! 0 facing +y; a chair faces a target when the ray out of its front meets the target's footprint;
//! a desk's front is the side its sitter sits at, so a chair at a desk faces the desk.
//!
//! Seats facing a focus: [`rows`] (and [`desk_rows`]), [`arc`]. Seats at a piece: [`ring`],
//! [`per_side`], [`along_front`]. Against a wall or an anchor: [`along_wall`], [`flanking_pair`],
//! [`one_per_member`]. Desks with chairs: [`pods`], [`l_workstation`], [`u_workstation`]. Tables
//! with seats round the outside: [`u_tables`].
//!
//! The guarantees, each a property test in `formation/tests.rs`: the asked count exactly; members
//! keep the asked gaps from each other and from the focus (separating lines, not sampling); the
//! members that should face the focus do; the same input gives the same output; rotating and
//! moving the input rotates and moves the output alike. Room walls are the caller's business:
//! [`footprints`] gives the members' footprints to test against a room.

use std::fmt;

use disco_core::geometry::{Footprint, normalize_degrees};
use disco_core::placement::{Pose, facing_rotation};
use glam::DVec2;

#[cfg(test)]
mod tests;

/// Default space (cm) between neighbouring seats of a row, an arc or a side.
pub const SEAT_SPACING_CM: f64 = 10.0;
/// Default space (cm) between a seat and the table or counter it is at.
pub const TABLE_GAP_CM: f64 = 5.0;
/// Default walkway (cm) between one row's back and the next row's front.
pub const ROW_AISLE_CM: f64 = disco_core::placement::ROW_AISLE_CM;
/// Default distance (cm) from the focus (screen, board, stage) to the first row.
pub const FIRST_ROW_CM: f64 = 200.0;
/// Default least distance (cm) from an arc's focus (a piano, a conductor) to its seats.
pub const ARC_CLEARANCE_CM: f64 = 60.0;
/// Default span (degrees) of an arc, first seat to last, seen from the focus: a semicircle.
pub const SEMICIRCLE_DEG: f64 = 180.0;
/// Default clear width (cm) of a shop's aisle, front to front: two people with baskets pass.
pub const AISLE_CM: f64 = 120.0;
/// Default walkway (cm) between two pods of desks.
pub const POD_AISLE_CM: f64 = 90.0;
/// Default space (cm) between a desk's front edge and its chair.
pub const CHAIR_GAP_CM: f64 = 5.0;
/// Default space (cm) between a member and the item in front of it (a music stand).
pub const STAND_DISTANCE_CM: f64 = 30.0;
/// Default space (cm) between an anchor and each flanking piece (nightstands beside a bed).
pub const FLANK_GAP_CM: f64 = 5.0;
/// Most members one formation may have; larger counts are refused, not allocated.
pub const MAX_MEMBERS: usize = 1000;

/// A member's width and depth (cm), as in an asset's `size = [width, depth, height]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Size {
    /// Along the member's local x (left to right, facing its front).
    pub width: f64,
    /// Along the member's local y (back to front).
    pub depth: f64,
}

impl Size {
    /// A `width` x `depth` member.
    pub const fn new(width: f64, depth: f64) -> Self {
        Size { width, depth }
    }
}

/// Why a formation could not be computed: which formation, and which input was wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct FormationError {
    /// The formation asked for (`rows`, `arc`, ...).
    pub formation: &'static str,
    /// What was wrong with its input.
    pub problem: String,
}

impl fmt::Display for FormationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "formation {}: {}", self.formation, self.problem)
    }
}

impl std::error::Error for FormationError {}

/// The result of a formation.
pub type Result<T> = std::result::Result<T, FormationError>;

/// Desks and their chairs: `chairs[i]` is the chair at `desks[i]` (in front of it, facing it).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Workstations {
    /// Desk poses (a desk's front is where its sitter sits).
    pub desks: Vec<Pose>,
    /// Chair poses, one per desk, in the desks' order.
    pub chairs: Vec<Pose>,
}

/// The footprints of `poses`, each `size`: what a caller tests against a room or other objects.
pub fn footprints(poses: &[Pose], size: Size) -> Vec<Footprint> {
    poses
        .iter()
        .map(|p| Footprint::new(p.center, size.width, size.depth, p.rotation))
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Rows

/// `count` seats in `rows` rows facing a focus; see [`rows`].
#[derive(Debug, Clone, PartialEq)]
pub struct RowsSpec {
    /// Seats in all.
    pub count: usize,
    /// Rows; the front rows take one more seat each when `count` does not divide evenly.
    pub rows: usize,
    /// Each seat's size.
    pub seat: Size,
    /// From the focus's footprint to the first row's near side (cm).
    pub first_row: f64,
    /// Between neighbouring seats of a row (cm).
    pub spacing: f64,
    /// Between one row and the next (cm).
    pub aisle: f64,
    /// Rotation (degrees) of the line from the focus out into the room; `None`: the focus's front.
    pub direction: Option<f64>,
    /// Turn each seat to the focus's centre instead of all facing straight back along the line.
    pub curved: bool,
}

impl RowsSpec {
    /// `count` seats of `seat` in `rows` rows, with the default distances and straight facing.
    pub fn new(count: usize, rows: usize, seat: Size) -> Self {
        RowsSpec {
            count,
            rows,
            seat,
            first_row: FIRST_ROW_CM,
            spacing: SEAT_SPACING_CM,
            aisle: ROW_AISLE_CM,
            direction: None,
            curved: false,
        }
    }
}

/// Seats in rows facing `focus`: "two rows of five recliners facing the screen".
///
/// The rows stand across the line from the focus's centre out along `direction`, centred on it;
/// the first row `first_row` cm beyond the focus's footprint, each next row `aisle` cm behind the
/// one before. Every seat faces back along the line (so the seats straight in front of the focus
/// face it), or with `curved` is turned exactly to the focus's centre (then the seats keep
/// `spacing` between their turned footprints). Order: the first row first; within a row from the
/// focus's left to its right (as the focus sees the room).
pub fn rows(focus: &Footprint, spec: &RowsSpec) -> Result<Vec<Pose>> {
    let check = Check("rows");
    check.footprint("focus", focus)?;
    check.count("count", spec.count)?;
    check.size("seat", spec.seat)?;
    check.lengths(&[
        ("first_row", spec.first_row),
        ("spacing", spec.spacing),
        ("aisle", spec.aisle),
    ])?;
    if spec.rows == 0 && spec.count > 0 {
        return Err(check.err("0 rows cannot hold any seat".into()));
    }
    let u = match spec.direction {
        Some(d) => check.angle("direction", d).map(|_| along(d))?,
        None => focus.front,
    };
    let v = right_of(u);
    let (hw, hd) = (spec.seat.width / 2.0, spec.seat.depth / 2.0);
    let mut near = support(focus, u) + spec.first_row;
    let mut out = Vec::with_capacity(spec.count);
    for k in split(spec.count, spec.rows) {
        let row = if spec.curved {
            curved_row(k, near, hw, hd, spec.spacing)
        } else {
            let xs = spaced(k, spec.seat.width + spec.spacing);
            Row {
                c: near + hd,
                xs,
                reach: hd,
            }
        };
        for &x in &row.xs {
            let p = focus.center + u * row.c + v * x;
            let rotation = if spec.curved {
                facing_rotation(p, focus.center)
            } else {
                rotation_of(-u)
            };
            out.push(pose(p, rotation));
        }
        near = row.c + row.reach + spec.aisle;
    }
    Ok(out)
}

/// Desks with chairs in rows facing `focus`: a classroom facing the board.
///
/// `spec.seat` is the chair; each chair sits behind its desk (further from the focus), `chair_gap`
/// cm from the desk's front edge, and faces the focus as in [`rows`]; each desk's front (where its
/// sitter sits) faces the chair. `spec.first_row` and `spec.aisle` are measured desk to focus and
/// chair to next desk. Order as in [`rows`]; `chairs[i]` sits at `desks[i]`.
pub fn desk_rows(
    focus: &Footprint,
    spec: &RowsSpec,
    desk: Size,
    chair_gap: f64,
) -> Result<Workstations> {
    let check = Check("desk rows");
    check.size("desk", desk)?;
    check.lengths(&[("chair_gap", chair_gap)])?;
    let chair = spec.seat;
    let unit = Size::new(
        desk.width.max(chair.width),
        desk.depth + chair_gap + chair.depth,
    );
    let units = rows(
        focus,
        &RowsSpec {
            seat: unit,
            ..spec.clone()
        },
    )?;
    let mut out = Workstations::default();
    for u in units {
        let f = along(u.rotation);
        let desk_c = u.center + f * (unit.depth - desk.depth) / 2.0;
        let chair_c = u.center - f * (unit.depth - chair.depth) / 2.0;
        out.desks.push(pose(desk_c, u.rotation + 180.0));
        out.chairs.push(pose(chair_c, u.rotation));
    }
    Ok(out)
}

/// One row of a formation in the line's frame: seats at lateral offsets `xs`, centres `c` out
/// along the line, reaching `reach` either side of `c` along it.
struct Row {
    c: f64,
    xs: Vec<f64>,
    reach: f64,
}

/// A row of `k` seats turned to the origin whose footprints stay beyond `near` along the line and
/// `spacing` apart across it: neighbours are placed outwards from the middle, each as close as
/// the projections of the turned footprints allow.
fn curved_row(k: usize, near: f64, hw: f64, hd: f64, spacing: f64) -> Row {
    let diag = hw.hypot(hd);
    // Half-extents across (p) and along (q) the line of a seat at (x, c) turned to the origin.
    let extents = |x: f64, c: f64| {
        let r = x.hypot(c);
        let (sin, cos) = if r > 0.0 {
            (x.abs() / r, c / r)
        } else {
            (0.0, 1.0)
        };
        (hw * cos + hd * sin, hw * sin + hd * cos)
    };
    let place = |c: f64| {
        let p = |x: f64| extents(x, c).0;
        // The least x' >= target whose seat's near side x' - p(x') clears `target`.
        let next = |target: f64| {
            let (mut lo, mut hi) = (target, target + diag);
            for _ in 0..100 {
                let mid = (lo + hi) / 2.0;
                if mid - p(mid) >= target {
                    hi = mid
                } else {
                    lo = mid
                }
            }
            hi
        };
        let mut half = Vec::with_capacity(k / 2 + 1);
        let mut x = if k % 2 == 1 { 0.0 } else { next(spacing / 2.0) };
        if k > 0 {
            half.push(x);
        }
        while half.len() < k.div_ceil(2) {
            x = next(x + p(x) + spacing);
            half.push(x);
        }
        // Mirror the right half to the left (the middle seat of an odd row only once).
        let mut xs: Vec<f64> = half[k % 2..].iter().rev().map(|x| -x).collect();
        xs.extend(&half);
        let reach = xs.iter().map(|&x| extents(x, c).1).fold(hd, f64::max);
        (xs, reach)
    };
    let mut c = near + hd;
    for _ in 0..16 {
        let (xs, reach) = place(c);
        if c - reach >= near - 1e-9 {
            return Row { c, xs, reach };
        }
        c = near + reach;
    }
    // A turned seat never reaches further than its half-diagonal.
    let c = near + diag;
    let (xs, reach) = place(c);
    Row { c, xs, reach }
}

// ---------------------------------------------------------------------------------------------
// Arc and ring

/// `count` seats on an arc around a focus; see [`arc`].
#[derive(Debug, Clone, PartialEq)]
pub struct ArcSpec {
    /// Seats in all.
    pub count: usize,
    /// Each seat's size.
    pub seat: Size,
    /// Degrees from the first seat to the last, seen from the focus's centre (360: a full ring).
    pub span: f64,
    /// Least space between neighbouring seats (cm).
    pub spacing: f64,
    /// Least distance from the focus's footprint to any seat (cm).
    pub clearance: f64,
    /// Least radius (cm) of the seats' centres, when a wider arc is wanted.
    pub min_radius: f64,
    /// Rotation (degrees) of the arc's middle seen from the focus; `None`: the focus's front.
    pub direction: Option<f64>,
}

impl ArcSpec {
    /// A semicircle of `count` seats of `seat` with the default distances.
    pub fn new(count: usize, seat: Size) -> Self {
        ArcSpec {
            count,
            seat,
            span: SEMICIRCLE_DEG,
            spacing: SEAT_SPACING_CM,
            clearance: ARC_CLEARANCE_CM,
            min_radius: 0.0,
            direction: None,
        }
    }
}

/// Seats on a circular arc around `focus`, each turned exactly to its centre: "six chairs in a
/// semicircle facing the piano".
///
/// The arc is centred on `direction` (default the focus's front) and spans `span` degrees between
/// its first and last seat, evenly; all seats stand at one radius, the least that keeps `spacing`
/// between neighbours, `clearance` from the focus's footprint and at least `min_radius`. Order:
/// from the focus's left to its right (as the focus sees the room).
pub fn arc(focus: &Footprint, spec: &ArcSpec) -> Result<Vec<Pose>> {
    let check = Check("arc");
    check.footprint("focus", focus)?;
    check.count("count", spec.count)?;
    check.size("seat", spec.seat)?;
    check.lengths(&[
        ("spacing", spec.spacing),
        ("clearance", spec.clearance),
        ("min_radius", spec.min_radius),
    ])?;
    let n = spec.count;
    if !(spec.span > 0.0 && spec.span <= 360.0) {
        return Err(check.err(format!(
            "span must be more than 0 and at most 360 degrees, got {}",
            spec.span
        )));
    }
    let middle = match spec.direction {
        Some(d) => check.angle("direction", d).map(|_| d)?,
        None => focus.rotation,
    };
    let full = spec.span >= 360.0 - 1e-9;
    let step = match n {
        0 | 1 => 0.0,
        _ if full => 360.0 / n as f64,
        _ => spec.span / (n - 1) as f64,
    };
    let angles: Vec<f64> = (0..n)
        .map(|i| middle + (i as f64 - (n as f64 - 1.0) / 2.0) * step)
        .collect();
    // The closest two seats, by angle: neighbours, or the two ends across the gap of the circle.
    let closest = (n >= 2).then(|| {
        if full {
            step
        } else {
            step.min(360.0 - spec.span)
        }
    });
    Ok(on_circle(
        focus,
        &angles,
        closest,
        spec.seat,
        spec.spacing,
        spec.clearance,
        spec.min_radius,
    ))
}

/// Seats at `angles` (degrees, seen from `focus`'s centre) on one circle, turned to its centre:
/// the least radius keeping `spacing` between seats `closest` degrees apart (the smallest angle
/// between any two), `clearance` from the focus's footprint, and at least `min_radius`.
fn on_circle(
    focus: &Footprint,
    angles: &[f64],
    closest: Option<f64>,
    seat: Size,
    spacing: f64,
    clearance: f64,
    min_radius: f64,
) -> Vec<Pose> {
    let (hw, hd) = (seat.width / 2.0, seat.depth / 2.0);
    // Two seats turned to the centre, `a` apart: their nearest points are the inner front
    // corners, mirror images across the bisector; each must lie spacing/2 from it.
    let neighbours = closest.map_or(0.0, |a| {
        let (s, c) = (a / 2.0).to_radians().sin_cos();
        hd + (spacing / 2.0 + hw * c.max(0.0)) / s
    });
    // Each seat lies beyond the line across its front edge; the focus within its support there.
    let off_focus = angles
        .iter()
        .map(|&a| support(focus, along(a)))
        .fold(0.0, f64::max)
        + clearance
        + hd;
    let radius = neighbours.max(off_focus).max(min_radius);
    angles
        .iter()
        .map(|&a| pose(focus.center + along(a) * radius, a + 180.0))
        .collect()
}

/// `count` seats around a piece; see [`ring`].
#[derive(Debug, Clone, PartialEq)]
pub struct RingSpec {
    /// Seats in all.
    pub count: usize,
    /// Each seat's size.
    pub seat: Size,
    /// The piece is round (its footprint is still the square around it).
    pub round: bool,
    /// Least space between a seat and the piece (cm).
    pub gap: f64,
    /// Least space between neighbouring seats (cm).
    pub spacing: f64,
}

impl RingSpec {
    /// `count` seats of `seat` around a piece (`round` or rectangular) with the default gaps.
    pub fn new(count: usize, seat: Size, round: bool) -> Self {
        RingSpec {
            count,
            seat,
            round,
            gap: TABLE_GAP_CM,
            spacing: SEAT_SPACING_CM,
        }
    }
}

/// Seats evenly around `piece`, each facing it: "eight chairs around the round table".
///
/// Round pieces: evenly by angle from the piece's front, clockwise, all at one radius, the least
/// keeping `gap` from the piece's (square) footprint and `spacing` between seats. Rectangular
/// pieces: the two long sides first, as many as fit there comfortably (front or right side one
/// more when odd), then the two ends, then any seats left over on the long sides (those rows then
/// overhang the corners, and the end seats move out to clear them). Order: side by side (long
/// side, the other long side, end, other end), each side clockwise around the piece.
pub fn ring(piece: &Footprint, spec: &RingSpec) -> Result<Vec<Pose>> {
    let check = Check("ring");
    check.footprint("piece", piece)?;
    check.count("count", spec.count)?;
    check.size("seat", spec.seat)?;
    check.lengths(&[("gap", spec.gap), ("spacing", spec.spacing)])?;
    let n = spec.count;
    if spec.round {
        let step = 360.0 / n.max(1) as f64;
        let angles: Vec<f64> = (0..n).map(|i| piece.rotation + i as f64 * step).collect();
        let closest = (n >= 2).then_some(step);
        return Ok(on_circle(
            piece,
            &angles,
            closest,
            spec.seat,
            spec.spacing,
            spec.gap,
            0.0,
        ));
    }
    let t = Table::of(piece);
    let fit = |half: f64| {
        ((2.0 * half + spec.spacing) / (spec.seat.width + spec.spacing)).floor() as usize
    };
    let long = n.min(fit(t.long_half).saturating_mul(2));
    let ends = (n - long).min(fit(t.end_half).saturating_mul(2));
    let long = n - ends;
    let counts = [long.div_ceil(2), long / 2, ends.div_ceil(2), ends / 2];
    Ok(t.seats(counts, spec.seat, spec.gap, spec.spacing))
}

/// `per_long` seats down each long side of `table`, plus one at each end when `ends`, each facing
/// the table, evenly spread along its side: "five chairs down each long side".
///
/// Seats stand `gap` from the table and at least `spacing` apart (a side with more seats than fit
/// overhangs the corners; the end seats then move out to clear them). Order: the front (or right,
/// when the table is deeper than wide) long side, the other long side, then the ends; each side
/// clockwise around the table.
pub fn per_side(
    table: &Footprint,
    seat: Size,
    per_long: usize,
    ends: bool,
    gap: f64,
    spacing: f64,
) -> Result<Vec<Pose>> {
    let check = Check("per side");
    check.footprint("table", table)?;
    check.count("per_long", per_long.saturating_mul(2))?;
    check.size("seat", seat)?;
    check.lengths(&[("gap", gap), ("spacing", spacing)])?;
    let e = usize::from(ends);
    Ok(Table::of(table).seats([per_long, per_long, e, e], seat, gap, spacing))
}

/// A table's long and short sides: outward normals, half-lengths, and the distance from its centre.
struct Table<'t> {
    t: &'t Footprint,
    long_n: DVec2,
    long_half: f64,
    long_off: f64,
    end_n: DVec2,
    end_half: f64,
    end_off: f64,
}

impl<'t> Table<'t> {
    fn of(t: &'t Footprint) -> Self {
        if t.half.x >= t.half.y {
            Table {
                t,
                long_n: t.front,
                long_half: t.half.x,
                long_off: t.half.y,
                end_n: t.right,
                end_half: t.half.y,
                end_off: t.half.x,
            }
        } else {
            Table {
                t,
                long_n: t.right,
                long_half: t.half.y,
                long_off: t.half.x,
                end_n: t.front,
                end_half: t.half.x,
                end_off: t.half.y,
            }
        }
    }

    /// Seats on the sides: `counts` for the long side, the opposite long side, the end and the
    /// opposite end. Long-side seats stand `gap` out; end seats too, or further when the long rows
    /// reach past the table's ends and the end rows past its long sides (they would meet at the
    /// corners).
    fn seats(&self, counts: [usize; 4], seat: Size, gap: f64, spacing: f64) -> Vec<Pose> {
        let pitch = |k: usize, half: f64| (2.0 * half / k.max(1) as f64).max(seat.width + spacing);
        let reach = |k: usize, half: f64| match k {
            0 => 0.0,
            _ => (k - 1) as f64 / 2.0 * pitch(k, half) + seat.width / 2.0,
        };
        let (long_k, end_k) = (counts[0].max(counts[1]), counts[2].max(counts[3]));
        let long_line = (self.long_off + gap).max(spacing / 2.0);
        let mut end_line = (self.end_off + gap).max(spacing / 2.0);
        let long_reach = reach(long_k, self.long_half);
        if long_k > 0
            && end_k > 0
            && long_reach + spacing > end_line
            && reach(end_k, self.end_half) + spacing > long_line
        {
            end_line = long_reach + spacing;
        }
        let sides = [
            (self.long_n, long_line, self.long_half),
            (-self.long_n, long_line, self.long_half),
            (self.end_n, end_line, self.end_half),
            (-self.end_n, end_line, self.end_half),
        ];
        let mut out = Vec::new();
        for ((normal, line, half), k) in sides.into_iter().zip(counts) {
            let tangent = right_of(normal);
            let base = self.t.center + normal * (line + seat.depth / 2.0);
            for x in spaced(k, pitch(k, half)) {
                out.push(pose(base + tangent * x, rotation_of(-normal)));
            }
        }
        out
    }
}

// ---------------------------------------------------------------------------------------------
// Along a piece, flanking, one per member

/// `count` members along the front edge of `piece`, each facing it: "four bar stools along the
/// island's front".
///
/// Members stand `gap` out from the front edge, spread evenly over its length and at least
/// `spacing` apart (more than fit overhang its ends, and those past the ends no longer face it).
/// Order: from the piece's left to its right.
pub fn along_front(
    piece: &Footprint,
    member: Size,
    count: usize,
    gap: f64,
    spacing: f64,
) -> Result<Vec<Pose>> {
    let check = Check("along front");
    check.footprint("piece", piece)?;
    check.count("count", count)?;
    check.size("member", member)?;
    check.lengths(&[("gap", gap), ("spacing", spacing)])?;
    let pitch = (2.0 * piece.half.x / count.max(1) as f64).max(member.width + spacing);
    let base = piece.center + piece.front * (piece.half.y + gap + member.depth / 2.0);
    Ok(spaced(count, pitch)
        .into_iter()
        .map(|x| pose(base + piece.right * x, piece.rotation + 180.0))
        .collect())
}

/// `count` members with their backs on the wall from `from` to `to`, facing into the room (on the
/// left of `from` -> `to`, as in a counter-clockwise outline): "a run of cabinets along the back
/// wall", "three bookcases along the left wall".
///
/// Members are spread evenly over the wall's length, at least `spacing` apart (more than fit run
/// past its ends: the caller checks the room). Order: from `from` towards `to`.
pub fn along_wall(
    from: DVec2,
    to: DVec2,
    member: Size,
    count: usize,
    spacing: f64,
) -> Result<Vec<Pose>> {
    let check = Check("along wall");
    check.point("from", from)?;
    check.point("to", to)?;
    check.count("count", count)?;
    check.size("member", member)?;
    check.lengths(&[("spacing", spacing)])?;
    let length = (to - from).length();
    if length <= 0.0 {
        return Err(check.err(format!("the wall has no length: {from} to {to}")));
    }
    let d = (to - from) / length;
    let inward = DVec2::new(-d.y, d.x);
    let pitch = (length / count.max(1) as f64).max(member.width + spacing);
    let base = (from + to) / 2.0 + inward * member.depth / 2.0;
    Ok(spaced(count, pitch)
        .into_iter()
        .map(|x| pose(base + d * x, rotation_of(inward)))
        .collect())
}

/// One member on each side of `anchor`, facing the same way, back edges in line with the anchor's
/// back edge, `gap` from its sides: "a nightstand on each side of the bed", "a lamp each side of
/// the sofa". Order: the anchor's left, then its right.
pub fn flanking_pair(anchor: &Footprint, member: Size, gap: f64) -> Result<Vec<Pose>> {
    let check = Check("flanking pair");
    check.footprint("anchor", anchor)?;
    check.size("member", member)?;
    check.lengths(&[("gap", gap)])?;
    let out = anchor.half.x + gap + member.width / 2.0;
    let back = anchor.front * (member.depth / 2.0 - anchor.half.y);
    Ok([-1.0, 1.0]
        .into_iter()
        .map(|side| {
            pose(
                anchor.center + anchor.right * side * out + back,
                anchor.rotation,
            )
        })
        .collect())
}

/// Checks the inputs of an item per member and returns how far (cm) each item's centre stands
/// from its member's: half the member's depth, the gap and half the item's.
fn item_offset(
    check: Check,
    members: &[Pose],
    member: Size,
    item: Size,
    distance: f64,
) -> Result<f64> {
    check.count("members", members.len())?;
    check.size("member", member)?;
    check.size("item", item)?;
    check.lengths(&[("distance", distance)])?;
    for m in members {
        check.point("member centre", m.center)?;
        check.angle("member rotation", m.rotation)?;
    }
    Ok(member.depth / 2.0 + distance + item.depth / 2.0)
}

/// One `item` in front of each member, `distance` cm from the member's front edge, facing the
/// member: "a music stand in front of each chair". Order: the members' order. The items are not
/// checked against each other: members closer than an item's width may need a smaller item.
pub fn one_per_member(
    members: &[Pose],
    member: Size,
    item: Size,
    distance: f64,
) -> Result<Vec<Pose>> {
    let out = item_offset(Check("one per member"), members, member, item, distance)?;
    Ok(members
        .iter()
        .map(|m| pose(m.center + along(m.rotation) * out, m.rotation + 180.0))
        .collect())
}

/// One `item` behind each member, `distance` cm from the member's back edge, turned the way
/// the member is (so the item's front faces the member's back): "each easel with a stool behind
/// it for the painter". Order: the members' order.
pub fn one_behind_each(
    members: &[Pose],
    member: Size,
    item: Size,
    distance: f64,
) -> Result<Vec<Pose>> {
    let out = item_offset(Check("one behind each"), members, member, item, distance)?;
    Ok(members
        .iter()
        .map(|m| pose(m.center - along(m.rotation) * out, m.rotation))
        .collect())
}

/// `count` seats evenly on a circle about the point `centre`, each facing it, the first at
/// `rotation` degrees (seen from the centre): a closed circle of chairs on a rug or in the
/// middle of a room. The radius is the least keeping `spacing` between neighbours, and at least
/// `min_radius`. Order: by angle from the first.
pub fn circle_about(
    centre: DVec2,
    rotation: f64,
    count: usize,
    seat: Size,
    spacing: f64,
    min_radius: f64,
) -> Result<Vec<Pose>> {
    let check = Check("circle");
    check.point("centre", centre)?;
    check.angle("rotation", rotation)?;
    check.count("count", count)?;
    check.size("seat", seat)?;
    check.lengths(&[("spacing", spacing), ("min_radius", min_radius)])?;
    let step = 360.0 / count.max(1) as f64;
    let angles: Vec<f64> = (0..count).map(|i| rotation + i as f64 * step).collect();
    // A point focus: its footprint reaches nowhere, so only the spacing and `min_radius` count.
    let point = Footprint::new(centre, 0.0, 0.0, 0.0);
    Ok(on_circle(
        &point,
        &angles,
        (count >= 2).then_some(step),
        seat,
        spacing,
        0.0,
        min_radius,
    ))
}

// ---------------------------------------------------------------------------------------------
// Desks: pods and the L workstation

/// Pods of desks in back-to-back pairs; see [`pods`].
#[derive(Debug, Clone, PartialEq)]
pub struct PodsSpec {
    /// Pods, side by side.
    pub pods: usize,
    /// Desks per pod (an odd one out stands in the front row, unpaired).
    pub per_pod: usize,
    /// Each desk's size.
    pub desk: Size,
    /// Each chair's size.
    pub chair: Size,
    /// Between a desk's front edge and its chair (cm).
    pub chair_gap: f64,
    /// Between neighbouring desks (or chairs) of a pod's row (cm); 0: side by side, touching.
    pub desk_gap: f64,
    /// Between two pods (cm).
    pub aisle: f64,
}

impl PodsSpec {
    /// `pods` pods of `per_pod` desks, with chairs, with the default gaps.
    pub fn new(pods: usize, per_pod: usize, desk: Size, chair: Size) -> Self {
        PodsSpec {
            pods,
            per_pod,
            desk,
            chair,
            chair_gap: CHAIR_GAP_CM,
            desk_gap: 0.0,
            aisle: POD_AISLE_CM,
        }
    }
}

/// Pods of desks centred on `anchor`: "two pods of four desks, each two pairs back to back".
///
/// Each pod is two rows of desks, backs touching: the front row faces `rotation` (its sitters sit
/// on that side), the back row the opposite way; a pod's desks stand side by side `desk_gap`
/// apart, and the pods side by side across `rotation`, `aisle` apart (measured between desks or
/// chairs, whichever reach further). Each chair stands `chair_gap` in front of its desk, facing it.
/// Order: pod by pod from the left (facing `rotation`); in a pod the front row left to right, then
/// the back row in the same columns, so the desk at column `i` of the front row is back to back
/// with desk `front_row_len + i`.
pub fn pods(anchor: DVec2, rotation: f64, spec: &PodsSpec) -> Result<Workstations> {
    let check = Check("pods");
    check.point("anchor", anchor)?;
    check.angle("rotation", rotation)?;
    check.count("desks", spec.pods.saturating_mul(spec.per_pod))?;
    check.size("desk", spec.desk)?;
    check.size("chair", spec.chair)?;
    check.lengths(&[
        ("chair_gap", spec.chair_gap),
        ("desk_gap", spec.desk_gap),
        ("aisle", spec.aisle),
    ])?;
    let (f, r) = (along(rotation), right_of(along(rotation)));
    let cols = spec.per_pod.div_ceil(2);
    let wide = spec.desk.width.max(spec.chair.width);
    let pitch = wide + spec.desk_gap;
    let pod_width = cols.saturating_sub(1) as f64 * pitch + wide;
    let to_chair = spec.desk.depth / 2.0 + spec.chair_gap + spec.chair.depth / 2.0;
    let mut out = Workstations::default();
    for pod_x in spaced(spec.pods, pod_width + spec.aisle) {
        let xs = spaced(cols, pitch);
        let back_row = spec.per_pod / 2;
        for (side, row) in [(1.0, &xs[..]), (-1.0, &xs[..back_row])] {
            for &x in row {
                let front = f * side;
                let desk = anchor + r * (pod_x + x) + front * spec.desk.depth / 2.0;
                let desk_rot = rotation_of(front);
                out.desks.push(pose(desk, desk_rot));
                out.chairs
                    .push(pose(desk + front * to_chair, desk_rot + 180.0));
            }
        }
    }
    Ok(out)
}

/// Sizes and spacing for [`aisles`].
#[derive(Debug, Clone, PartialEq)]
pub struct AislesSpec {
    /// How many units (shelves, gondolas, racks).
    pub count: usize,
    /// How many lines they stand in.
    pub lines: usize,
    /// One unit's size; its front is the side customers take things from.
    pub unit: Size,
    /// Clear width (cm) of each aisle, front to front.
    pub aisle: f64,
    /// Between neighbouring units of a line (cm); 0: end to end.
    pub gap: f64,
}

impl AislesSpec {
    /// `count` units in `lines` lines, with the default aisle ([`AISLE_CM`]), end to end.
    pub fn new(count: usize, lines: usize, unit: Size) -> Self {
        AislesSpec {
            count,
            lines,
            unit,
            aisle: AISLE_CM,
            gap: 0.0,
        }
    }
}

/// Shelving in parallel lines with an aisle between each two facing lines, centred on
/// `anchor`: "a few aisles of shelves".
///
/// Each line runs along the right of `rotation`, its units end to end `gap` apart; the lines
/// stack along `rotation`'s front. The first line faces `rotation`, across the first aisle
/// from the second, which faces back at it; the second and third stand back to back (a
/// double-sided run, `gap` apart), the third faces across the next aisle to the fourth, and so on. So every
/// aisle has unit fronts on both sides, and no unit's front faces another's back. Units are
/// split over the lines as evenly as possible, the earlier lines taking one more. Order: line by
/// line from the first, each from its left (facing `rotation`).
pub fn aisles(anchor: DVec2, rotation: f64, spec: &AislesSpec) -> Result<Vec<Pose>> {
    let check = Check("aisles");
    check.point("anchor", anchor)?;
    check.angle("rotation", rotation)?;
    check.count("units", spec.count)?;
    check.size("unit", spec.unit)?;
    check.lengths(&[("aisle", spec.aisle), ("gap", spec.gap)])?;
    if spec.lines == 0 && spec.count > 0 {
        return Err(check.err("lines must be 1 or more".into()));
    }
    let (f, r) = (along(rotation), right_of(along(rotation)));
    let per_line = split(spec.count, spec.lines);
    let depth = spec.unit.depth;
    // Each line's offset along the front, and whether it faces the front.
    let mut offsets: Vec<(f64, bool)> = Vec::with_capacity(per_line.len());
    let mut at = 0.0;
    for k in 0..per_line.len() {
        if k > 0 {
            at += depth + if k % 2 == 1 { spec.aisle } else { spec.gap };
        }
        offsets.push((at, k % 2 == 0));
    }
    let middle = at / 2.0;
    let mut out = Vec::with_capacity(spec.count);
    for (&(offset, forward), &k) in offsets.iter().zip(&per_line) {
        let front = if forward { f } else { -f };
        for x in spaced(k, spec.unit.width + spec.gap) {
            // Seen facing `rotation`, left to right; a unit facing back is turned round.
            let centre = anchor + f * (offset - middle) + r * x;
            out.push(pose(centre, rotation_of(front)));
        }
    }
    Ok(out)
}

/// Sizes for [`l_workstation`].
#[derive(Debug, Clone, PartialEq)]
pub struct LSpec {
    /// The desk against the first wall (it reaches into the corner).
    pub desk_a: Size,
    /// The desk against the second wall (its end meets the first desk's front).
    pub desk_b: Size,
    /// The chair's size.
    pub chair: Size,
    /// Least space between the chair and either desk (cm).
    pub chair_gap: f64,
}

/// Two desks forming an L in a corner, and the chair in the crook facing the corner: "an L-shaped
/// workstation in the corner, the chair in the crook".
///
/// `corner` is where the walls meet; `wall_a` and `wall_b` point from it along the two walls (the
/// room lies between them; any angle short of 180°). Desk A stands with its back on wall A, as
/// close to the corner as wall B allows; desk B with its back on wall B, its end against desk A's
/// front line. The chair stands on the line from the corner through the L's inner corner, beyond
/// both desks' fronts by at least `chair_gap`, facing the corner (in a right-angled corner, with
/// desk B shallower than desk A is wide, its view crosses desk A). Order: desks `[A, B]`, one chair.
pub fn l_workstation(
    corner: DVec2,
    wall_a: DVec2,
    wall_b: DVec2,
    spec: &LSpec,
) -> Result<Workstations> {
    let check = Check("L workstation");
    check.point("corner", corner)?;
    check.point("wall_a", wall_a)?;
    check.point("wall_b", wall_b)?;
    check.size("desk_a", spec.desk_a)?;
    check.size("desk_b", spec.desk_b)?;
    check.size("chair", spec.chair)?;
    check.lengths(&[("chair_gap", spec.chair_gap)])?;
    let (a, b) = (wall_a.normalize_or_zero(), wall_b.normalize_or_zero());
    let sin = a.perp_dot(b).abs();
    if a == DVec2::ZERO || b == DVec2::ZERO || sin < 1e-6 {
        return Err(check.err(format!(
            "the walls must point two different ways from the corner, got {wall_a} and {wall_b}"
        )));
    }
    let cos = a.dot(b);
    // Inward normals: wall A's towards wall B's side, and back.
    let na = (b - a * cos).normalize();
    let nb = (a - b * cos).normalize();
    let (da, db) = (spec.desk_a, spec.desk_b);
    // Along wall A, desk A's corners keep to wall B's inner side; desk B's to desk A's front.
    let sa = da.width / 2.0 + (da.depth * cos).max(0.0) / sin;
    let sb = db.width / 2.0 + (da.depth + (db.depth * cos).max(0.0)) / sin;
    let desk_a = pose(corner + a * sa + na * da.depth / 2.0, rotation_of(na));
    let desk_b = pose(corner + b * sb + nb * db.depth / 2.0, rotation_of(nb));
    // The inner corner of the L: depth A out from wall A and depth B out from wall B.
    let inner = corner + solve(na, nb, da.depth, db.depth);
    let v = (inner - corner).normalize();
    let chair_fp = Footprint::new(
        DVec2::ZERO,
        spec.chair.width,
        spec.chair.depth,
        rotation_of(-v),
    );
    let t = [na, nb]
        .into_iter()
        .map(|n| (spec.chair_gap + support(&chair_fp, n)) / v.dot(n))
        .fold(0.0, f64::max);
    Ok(Workstations {
        desks: vec![desk_a, desk_b],
        chairs: vec![pose(inner + v * t, rotation_of(-v))],
    })
}

/// Sizes for [`u_workstation`].
#[derive(Debug, Clone, PartialEq)]
pub struct USpec {
    /// The desk across the back of the U.
    pub main: Size,
    /// Each of the two desks down the U's sides.
    pub side: Size,
    /// The chair's size.
    pub chair: Size,
    /// Space between the chair and the main desk, and least space to the side desks (cm).
    pub chair_gap: f64,
}

/// Three desks in a U and the chair inside it facing the back desk: "a U-shaped workstation".
///
/// The main desk's back edge is centred on `anchor` (a point on a wall, say) and it faces
/// `rotation`; a side desk stands at each end of it, its outer edge in line with the main desk's
/// end, its end against the main desk's front, facing into the U. The chair stands `chair_gap` in
/// front of the main desk, on its centre line, facing it. Refused when the U is too narrow for the
/// chair to keep `chair_gap` from the side desks. Order: desks `[main, left side, right side]`
/// (left facing `rotation`), one chair.
pub fn u_workstation(anchor: DVec2, rotation: f64, spec: &USpec) -> Result<Workstations> {
    let check = Check("U workstation");
    check.point("anchor", anchor)?;
    check.angle("rotation", rotation)?;
    check.size("main", spec.main)?;
    check.size("side", spec.side)?;
    check.size("chair", spec.chair)?;
    check.lengths(&[("chair_gap", spec.chair_gap)])?;
    let (m, sd, c) = (spec.main, spec.side, spec.chair);
    let inside = m.width - 2.0 * sd.depth;
    if c.width + 2.0 * spec.chair_gap > inside {
        return Err(check.err(format!(
            "a {} cm chair does not fit the U's {inside} cm inside with {} cm either side",
            c.width, spec.chair_gap
        )));
    }
    let (f, r) = (along(rotation), right_of(along(rotation)));
    let main = pose(anchor + f * m.depth / 2.0, rotation);
    let sides = [-1.0, 1.0].map(|side| {
        let centre =
            anchor + r * side * (m.width - sd.depth) / 2.0 + f * (m.depth + sd.width / 2.0);
        pose(centre, rotation_of(r * -side))
    });
    let chair = anchor + f * (m.depth + spec.chair_gap + c.depth / 2.0);
    Ok(Workstations {
        desks: vec![main, sides[0], sides[1]],
        chairs: vec![pose(chair, rotation + 180.0)],
    })
}

/// Least clear width (cm) inside a U of tables whose arms stand on its base's front: a narrower
/// inside has the arms flank the base instead.
pub const U_INSIDE_CM: f64 = 120.0;

/// Tables in a U and their seats; see [`u_tables`].
#[derive(Debug, Clone, PartialEq)]
pub struct UTablesSpec {
    /// Each table's size (its width runs along the U's side it stands in).
    pub table: Size,
    /// Each seat's size.
    pub seat: Size,
    /// Seats at each table, in the tables' order (see [`u_tables`]); its length is the number
    /// of tables (3 or more).
    pub seats: Vec<usize>,
    /// Between a table's outer edge and its seats (cm).
    pub seat_gap: f64,
}

impl UTablesSpec {
    /// `seats.len()` tables with `seats[i]` seats at table `i`, the default gap.
    pub fn new(table: Size, seat: Size, seats: Vec<usize>) -> Self {
        UTablesSpec {
            table,
            seat,
            seats,
            seat_gap: TABLE_GAP_CM,
        }
    }
}

/// Tables of a U and the seats round its outside.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct UTables {
    /// Table poses (a table's front is its seat side: outwards).
    pub tables: Vec<Pose>,
    /// Seat poses, table by table in the tables' order, each facing its table.
    pub seats: Vec<Pose>,
    /// How far (cm) the U reaches back from its open end, seats included.
    pub depth: f64,
    /// How wide (cm) the U is across, seats included.
    pub width: f64,
}

/// How `n` tables split over a U: (tables down each arm, tables across the base); `None` for
/// fewer than 3.
pub fn u_split(n: usize) -> Option<(usize, usize)> {
    if n < 3 {
        return None;
    }
    let mut side = n.div_ceil(3);
    while n < 2 * side + 1 {
        side -= 1;
    }
    Some((side, n - 2 * side))
}

/// Tables in a U whose open end is centred on `anchor` and faces `rotation` (towards a screen):
/// "six tables in a U facing the screen, chairs round the outside".
///
/// The tables split by [`u_split`]: the base across the back, the arms running from it to the
/// open end, every table's long side along its part of the U. The arms stand on the base's
/// front, their outer edges in line with its ends, when that leaves [`U_INSIDE_CM`] clear
/// inside; otherwise they flank the base. Each table's seats stand along its outer long edge,
/// `seat_gap` out, spread evenly along it (refused when they are too wide for it), facing in; every table faces out (its front is its
/// seat side). Order of the tables: the left arm (facing `rotation`) from the open end, the
/// base left to right, the right arm from the base to the open end; the seats table by table.
pub fn u_tables(anchor: DVec2, rotation: f64, spec: &UTablesSpec) -> Result<UTables> {
    let check = Check("U of tables");
    check.point("anchor", anchor)?;
    check.angle("rotation", rotation)?;
    let n = spec.seats.len();
    check.count("tables", n)?;
    check.count(
        "seats",
        spec.seats.iter().fold(0usize, |a, &k| a.saturating_add(k)),
    )?;
    check.size("table", spec.table)?;
    check.size("seat", spec.seat)?;
    check.lengths(&[("seat_gap", spec.seat_gap)])?;
    let Some((side, across)) = u_split(n) else {
        return Err(check.err(format!("a U needs 3 tables or more, got {n}")));
    };
    let (tw, td) = (spec.table.width, spec.table.depth);
    if let Some(&k) = spec.seats.iter().max()
        && k as f64 * spec.seat.width > tw + 1e-9
    {
        return Err(check.err(format!(
            "{k} seats {} cm wide do not fit along a {tw} cm table",
            spec.seat.width
        )));
    }
    let (f, r) = (along(rotation), right_of(along(rotation)));
    let base_width = across as f64 * tw;
    let arm = side as f64 * tw;
    let inset = base_width - 2.0 * td >= U_INSIDE_CM;
    // Across: the arms' centre lines; back: the base's centre line (behind the open end).
    let (arm_x, base_y) = if inset {
        ((base_width - td) / 2.0, -(arm + td / 2.0))
    } else {
        ((base_width + td) / 2.0, -(arm - td / 2.0))
    };
    let out_seat = td / 2.0 + spec.seat_gap + spec.seat.depth / 2.0;
    let mut tables: Vec<(Pose, DVec2)> = Vec::with_capacity(n);
    // Left arm from the open end, its front to the left.
    for k in 0..side {
        let y = -(k as f64 + 0.5) * tw;
        tables.push((pose(anchor + f * y - r * arm_x, rotation_of(-r)), -r));
    }
    for x in spaced(across, tw) {
        tables.push((pose(anchor + f * base_y + r * x, rotation_of(-f)), -f));
    }
    for k in (0..side).rev() {
        let y = -(k as f64 + 0.5) * tw;
        tables.push((pose(anchor + f * y + r * arm_x, rotation_of(r)), r));
    }
    let mut seats = Vec::new();
    for ((t, out), &k) in tables.iter().zip(&spec.seats) {
        let pitch = tw / k.max(1) as f64;
        let along_edge = right_of(*out);
        for x in spaced(k, pitch) {
            let c = t.center + *out * out_seat + along_edge * x;
            seats.push(pose(c, rotation_of(-*out)));
        }
    }
    let depth = if inset {
        arm + td + spec.seat_gap + spec.seat.depth
    } else {
        arm + spec.seat_gap + spec.seat.depth
    };
    let width = 2.0 * (arm_x + td / 2.0 + spec.seat_gap + spec.seat.depth);
    Ok(UTables {
        tables: tables.into_iter().map(|(p, _)| p).collect(),
        seats,
        depth,
        width,
    })
}

/// The point `p` with `p·n1 = d1` and `p·n2 = d2`.
fn solve(n1: DVec2, n2: DVec2, d1: f64, d2: f64) -> DVec2 {
    let det = n1.perp_dot(n2);
    DVec2::new(d1 * n2.y - d2 * n1.y, n1.x * d2 - n2.x * d1) / det
}

// ---------------------------------------------------------------------------------------------
// Shared helpers

/// The unit vector a member turned `rotation` degrees faces.
fn along(rotation: f64) -> DVec2 {
    let (s, c) = rotation.to_radians().sin_cos();
    DVec2::new(s, c)
}

/// The rotation whose front is `v`.
fn rotation_of(v: DVec2) -> f64 {
    facing_rotation(DVec2::ZERO, v)
}

/// The right-hand side of a member whose front is `front`.
fn right_of(front: DVec2) -> DVec2 {
    DVec2::new(front.y, -front.x)
}

/// How far `fp` reaches from its centre along the unit vector `d`.
fn support(fp: &Footprint, d: DVec2) -> f64 {
    fp.half.x * fp.right.dot(d).abs() + fp.half.y * fp.front.dot(d).abs()
}

fn pose(center: DVec2, rotation: f64) -> Pose {
    Pose {
        center,
        rotation: normalize_degrees(rotation),
    }
}

/// `k` offsets `pitch` apart, centred on 0, ascending.
fn spaced(k: usize, pitch: f64) -> Vec<f64> {
    (0..k)
        .map(|i| (i as f64 - (k as f64 - 1.0) / 2.0) * pitch)
        .collect()
}

/// `count` split into `parts` near-equal parts, the larger first.
fn split(count: usize, parts: usize) -> Vec<usize> {
    let parts = parts.min(count);
    (0..parts)
        .map(|i| count / parts + usize::from(i < count % parts))
        .collect()
}

/// Input checks of one formation, with errors naming it.
struct Check(&'static str);

impl Check {
    fn err(&self, problem: String) -> FormationError {
        FormationError {
            formation: self.0,
            problem,
        }
    }

    fn size(&self, what: &str, s: Size) -> Result<()> {
        let ok = |v: f64| v.is_finite() && v > 0.0;
        if ok(s.width) && ok(s.depth) {
            Ok(())
        } else {
            Err(self.err(format!(
                "{what} size must be positive, got {} x {} cm",
                s.width, s.depth
            )))
        }
    }

    fn lengths(&self, all: &[(&str, f64)]) -> Result<()> {
        match all.iter().find(|(_, v)| !(v.is_finite() && *v >= 0.0)) {
            Some((what, v)) => Err(self.err(format!("{what} must be 0 cm or more, got {v}"))),
            None => Ok(()),
        }
    }

    fn angle(&self, what: &str, v: f64) -> Result<()> {
        if v.is_finite() {
            Ok(())
        } else {
            Err(self.err(format!("{what} must be a number of degrees, got {v}")))
        }
    }

    fn point(&self, what: &str, p: DVec2) -> Result<()> {
        if p.is_finite() {
            Ok(())
        } else {
            Err(self.err(format!("{what} must be finite, got {p}")))
        }
    }

    fn count(&self, what: &str, n: usize) -> Result<()> {
        if n <= MAX_MEMBERS {
            Ok(())
        } else {
            Err(self.err(format!("{what}: {n} members, more than {MAX_MEMBERS}")))
        }
    }

    fn footprint(&self, what: &str, fp: &Footprint) -> Result<()> {
        self.point(what, fp.center)?;
        self.angle(what, fp.rotation)?;
        if fp.half.is_finite() && fp.half.x >= 0.0 && fp.half.y >= 0.0 {
            Ok(())
        } else {
            Err(self.err(format!("{what} size must be finite, got {}", fp.half * 2.0)))
        }
    }
}
