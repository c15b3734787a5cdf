//! Formations the plan asks for (rows, an arc, seats per side, pods, one per member): every
//! member's pose computed at once by the shape's exact function (`disco_tools::formation`), the
//! variant that fits the room best, and handed out as each member's first candidate.
//!
//! A formation about a focus (the piano of an arc) is laid out once the focus stands; pods,
//! which stand on their own, when their first desk comes up, where the whole block fits nearest
//! the main area's middle. Chairs at the desks of rows and pods come with their desks.

use std::collections::HashMap;

use glam::DVec2;

use super::agent::RuleDesigner;
use super::brief::{GroupBrief, room_centre, target_of};
use super::draft::Draft;
use disco_core::geometry::Footprint;
use disco_core::placement::{self, Pose};
use disco_core::plan::{Formation, FormationShape, Relation};
use disco_core::scene::Asset;
use disco_tools::formation::{
    self as shape, AISLE_CM, AislesSpec, ArcSpec, CHAIR_GAP_CM, FIRST_ROW_CM, PodsSpec, RingSpec,
    RowsSpec, SEAT_SPACING_CM, STAND_DISTANCE_CM, Size, TABLE_GAP_CM, Workstations,
};

/// Arc variants tried, widest first: (span in degrees, clearance from the focus in cm).
const ARC_VARIANTS: [(f64, f64); 6] = [
    (180.0, 45.0),
    (150.0, 45.0),
    (120.0, 40.0),
    (200.0, 45.0),
    (100.0, 30.0),
    (80.0, 30.0),
];

/// Turns (degrees) of an arc's middle away from the focus's front tried, when the room cuts
/// the straight one short.
const ARC_TURNS: [f64; 9] = [0.0, -15.0, 15.0, -30.0, 30.0, -45.0, 45.0, -60.0, 60.0];

/// Sideways slides (cm) of rows along their focus tried, when the room cuts the straight ones
/// short (a focus near a corner).
const ROW_SHIFTS: [f64; 11] = [
    0.0, -60.0, 60.0, -120.0, 120.0, -180.0, 180.0, -240.0, 240.0, -300.0, 300.0,
];

/// Distances (cm) from the focus to the first row tried: the default, then nearer; then
/// farther, for rows something by the focus (a side door's swing) keeps back.
const FIRST_ROWS: [f64; 5] = [FIRST_ROW_CM, 150.0, 100.0, 260.0, 320.0];

/// Walkway (cm) between one row's chairs and the next row: a person (40 cm) walks along it to
/// every seat.
const ROWS_AISLE_CM: f64 = 60.0;

/// How much of a bare wall rows turned to it face (cm): the middle of it, as wide as a board.
const BARE_WALL_FOCUS_CM: f64 = 200.0;

/// Space (cm) between neighbouring desks of a row.
const DESK_SPACING_CM: f64 = 45.0;

/// Grid step (cm) of the search for where a block of pods stands.
const POD_STEP_CM: f64 = 20.0;

/// Width (cm) of the aisle between the benches of a row: a procession walks it.
const CENTRE_AISLE_CM: f64 = 120.0;

/// Most lines of shelving one block of aisles is tried with.
const MAX_AISLE_LINES: usize = 8;

/// Clear floor (cm) kept round every unit of a block of aisles, from the walls and from what
/// stands already: the ends of the aisles stay open, and the outer lines can be reached.
const AISLE_END_CM: f64 = 60.0;

/// A chair's size when a desk of a formation has none to take it from.
const CHAIR_CM: Size = Size::new(50.0, 50.0);

impl RuleDesigner {
    /// The pose the plan's formation gives `asset`, laid out now if it is due; `None` when the
    /// asset is in no formation, or its focus does not stand yet.
    pub(super) fn formation_pose(
        &self,
        brief: &GroupBrief<'_>,
        draft: &mut Draft<'_, '_>,
        asset: &Asset,
    ) -> Option<Pose> {
        if let Some(p) = draft.formation.get(&asset.name) {
            return Some(*p);
        }
        let plan = brief.plan;
        let f = plan.formation_of(&asset.name).or_else(|| {
            // A chair at a desk of rows or pods comes with its desk's formation.
            let (_, desk) = target_of(plan, &asset.name)?;
            plan.formation_of(desk)
                .filter(|f| matches!(f.shape, FormationShape::Rows | FormationShape::Pods))
        })?;
        // A formation the room cannot hold is laid out once per attempt, not once per member.
        let key = f.members.first()?.clone();
        if draft.formations_failed.contains(&key) {
            return None;
        }
        let Some((poses, variant)) = self.lay_out(brief, draft, f) else {
            draft.formations_failed.insert(key);
            return None;
        };
        // A formation the room made bend (a turned or narrowed arc, rows pulled closer) is
        // worth another pose of its focus: the group's cost counts it.
        if variant > 0 {
            draft.formations_bent += 1;
        }
        draft.formation.extend(poses);
        draft.formation.get(&asset.name).copied()
    }

    /// Every pose of formation `f`, by name, in the variant where most members fit, and which
    /// variant that is (0: the shape's own defaults).
    fn lay_out(
        &self,
        brief: &GroupBrief<'_>,
        draft: &Draft<'_, '_>,
        f: &Formation,
    ) -> Option<(HashMap<String, Pose>, usize)> {
        let asset = |n: &str| brief.group.iter().find(|a| a.name == n).copied();
        let members: Vec<&Asset> = f.members.iter().filter_map(|n| asset(n)).collect();
        let first = *members.first()?;
        let seat = Size::new(first.size[0], first.size[1]);
        let n = members.len();
        let focus = match &f.focus {
            // A U of tables whose focus is not posed yet (a TV hung with the wall pieces)
            // opens to the wall opposite the door.
            Some(name) if f.shape == FormationShape::UTables => {
                draft.where_is.get(name.as_str()).copied()
            }
            Some(name) => Some(*draft.where_is.get(name.as_str())?),
            // Rows turned to a bare wall face a stretch of it in its middle.
            None if f.shape == FormationShape::Rows => brief
                .rows_wall
                .get(first.name.as_str())
                .and_then(|role| brief.analysis.walls_with(*role).first().copied())
                .and_then(|i| brief.room.walls().into_iter().find(|w| w.index == i))
                .map(|w| {
                    let n = w.inward_normal();
                    let width = w.length().min(BARE_WALL_FOCUS_CM);
                    Footprint::new(
                        w.point(w.length() / 2.0) + n,
                        width,
                        2.0,
                        n.x.atan2(n.y).to_degrees(),
                    )
                }),
            None => None,
        };
        // Each desk's chairs: the objects whose first relation is to it (two at a double desk).
        let chairs_at: Vec<Vec<&Asset>> = members
            .iter()
            .map(|d| {
                brief
                    .group
                    .iter()
                    .copied()
                    .filter(|a| {
                        target_of(brief.plan, &a.name).is_some_and(|(_, t)| t == d.name)
                            && !f.members.contains(&a.name)
                    })
                    .collect()
            })
            .collect();
        let chairs: Vec<Option<&Asset>> = chairs_at.iter().map(|c| c.first().copied()).collect();
        let chair = chairs
            .iter()
            .flatten()
            .next()
            .map_or(CHAIR_CM, |c| Size::new(c.size[0], c.size[1]));
        let desks = members.iter().all(|a| a.category.contains("desk"));
        // A focus that is a floor covering (a rug): seats stand on it.
        let flat = |name: &str| {
            brief
                .placed
                .iter()
                .map(|p| (p.name.as_str(), p.size))
                .chain(brief.group.iter().map(|a| (a.name.as_str(), a.size)))
                .any(|(n, size)| n == name && size[2] <= disco_core::scene::FLAT_HEIGHT_CM)
        };
        let named = |ws: Workstations| -> HashMap<String, Pose> {
            let mut out = HashMap::new();
            for (k, m) in members.iter().enumerate() {
                if let Some(p) = ws.desks.get(k) {
                    out.insert(m.name.clone(), *p);
                }
                if let (Some(at), Some(p)) = (chairs_at.get(k), ws.chairs.get(k)) {
                    out.extend(side_by_side(at, p, m.size[0]));
                }
            }
            out
        };
        let seats_only = |poses: Vec<Pose>| -> HashMap<String, Pose> {
            members
                .iter()
                .zip(poses)
                .map(|(m, p)| (m.name.clone(), p))
                .collect()
        };
        let variants: Vec<HashMap<String, Pose>> = match (f.shape, focus) {
            (FormationShape::Arc, Some(t)) => {
                // Room before each seat for what stands in front of it (a music stand).
                let items: Vec<&Asset> = brief
                    .plan
                    .formations
                    .iter()
                    .filter(|o| o.shape == FormationShape::OnePerMember)
                    .filter(|o| o.of.iter().any(|m| f.members.contains(m)))
                    .filter_map(|o| o.members.first().and_then(|m| asset(m)))
                    .collect();
                let largest = |k: usize| items.iter().map(|i| i.size[k]).fold(0.0, f64::max);
                let before = match items.is_empty() {
                    true => 0.0,
                    false => largest(1) + STAND_DISTANCE_CM + SEAT_SPACING_CM,
                };
                // What stands before the seats stands on a smaller arc: the seats spread so
                // those items keep their own width apart.
                let item_width = largest(0);
                let spread = if before > 0.0 {
                    Size::new(
                        seat.width.max(item_width) + 2.0 * SEAT_SPACING_CM,
                        seat.depth,
                    )
                } else {
                    seat
                };
                ARC_VARIANTS
                    .iter()
                    .flat_map(|&v| ARC_TURNS.iter().map(move |&turn| (v, turn)))
                    .filter_map(|((span, clearance), turn)| {
                        let spec = ArcSpec {
                            span,
                            clearance: clearance + before,
                            direction: Some(t.rotation + turn),
                            ..ArcSpec::new(n, spread)
                        };
                        shape::arc(&t, &spec).ok().map(seats_only)
                    })
                    .collect()
            }
            // A closed circle on a rug: the seats on its rim, facing its middle.
            (FormationShape::Ring, Some(t)) if f.focus.as_deref().is_some_and(flat) => {
                let rim = t.half.x.min(t.half.y) - seat.depth / 2.0 - TABLE_GAP_CM;
                shape::circle_about(t.center, t.rotation, n, seat, SEAT_SPACING_CM, rim.max(0.0))
                    .ok()
                    .map(seats_only)
                    .into_iter()
                    .collect()
            }
            (FormationShape::Ring, Some(t)) => shape::ring(&t, &RingSpec::new(n, seat, false))
                .ok()
                .map(seats_only)
                .into_iter()
                .collect(),
            // A closed circle about nothing: where it fits nearest the room's middle.
            (FormationShape::Ring, None) => {
                let block = |_: f64| {
                    shape::circle_about(DVec2::ZERO, 0.0, n, seat, SEAT_SPACING_CM, 0.0)
                        .ok()
                        .map(&seats_only)
                };
                return self.place_block(brief, draft, &block, 0.0).map(|p| (p, 0));
            }
            // At a desk (seated at its front), a worker and `count` visitors: the worker alone
            // in the middle of the front, the visitors down the other side.
            (FormationShape::PerSide, Some(t))
                if f.count.is_some_and(|c| c >= 1 && n == c + 1)
                    && f.focus.as_deref().and_then(asset).is_some_and(|d| {
                        self.knowledge.kind_of(d).seats == Some(crate::knowledge::SeatsAt::Front)
                    }) =>
            {
                let k = n - 1;
                let worker =
                    shape::per_side(&t, seat, 1, false, TABLE_GAP_CM, SEAT_SPACING_CM).ok();
                let visitors =
                    shape::per_side(&t, seat, k, false, TABLE_GAP_CM, SEAT_SPACING_CM).ok();
                match (worker, visitors) {
                    (Some(w), Some(v)) => {
                        let mut poses = vec![w[0]];
                        poses.extend_from_slice(&v[k..2 * k]);
                        vec![seats_only(poses)]
                    }
                    _ => Vec::new(),
                }
            }
            (FormationShape::PerSide, Some(t)) => {
                let per_long = f.count.unwrap_or(n.div_ceil(2)).max(1);
                let ends = n > 2 * per_long;
                shape::per_side(&t, seat, per_long, ends, TABLE_GAP_CM, SEAT_SPACING_CM)
                    .ok()
                    .map(seats_only)
                    .into_iter()
                    .collect()
            }
            (FormationShape::AlongFront, Some(t)) => {
                shape::along_front(&t, seat, n, TABLE_GAP_CM, SEAT_SPACING_CM)
                    .ok()
                    .map(seats_only)
                    .into_iter()
                    .collect()
            }
            (FormationShape::Rows, Some(t)) => {
                let rows = f.count.unwrap_or(n.div_ceil(4)).clamp(1, n);
                // A focus lying on the floor (the instructor's mat) has no front of its own:
                // the rows stand on the side of it towards the room's middle.
                // A focus turned to the piece it stands before (the lectern to the screen
                // behind it: the speaker's side) has the rows at its back.
                let before_what_it_faces = |name: &str| {
                    brief.plan.constraints.get(name).is_some_and(|c| {
                        c.facing.as_deref().is_some_and(|t| {
                            c.relations
                                .iter()
                                .any(|r| r.relation == Relation::InFrontOf && r.target == t)
                        })
                    })
                };
                let t = match f.focus.as_deref() {
                    Some(name) if before_what_it_faces(name) => {
                        t.with_pose(t.center, (t.rotation + 180.0).rem_euclid(360.0))
                    }
                    Some(name) if flat(name) => {
                        let to_middle =
                            placement::facing_rotation(t.center, room_centre(brief.room));
                        t.with_pose(t.center, placement::snap90(to_middle))
                    }
                    _ => t,
                };
                // The rows straight before the focus first, then slid sideways along it (a
                // board or an altar off the room's middle), each at every first-row distance.
                ROW_SHIFTS
                    .iter()
                    .flat_map(|&dx| FIRST_ROWS.iter().map(move |&first_row| (dx, first_row)))
                    .map(|(dx, first_row)| {
                        let slid = t.with_pose(t.center + t.right * dx, t.rotation);
                        (slid, first_row, ROWS_AISLE_CM)
                    })
                    .filter_map(|(t, first_row, aisle)| {
                        if desks {
                            // Desks stand a walkway apart: each sitter reaches their seat
                            // from the side.
                            let spec = RowsSpec {
                                first_row,
                                aisle,
                                spacing: DESK_SPACING_CM,
                                ..RowsSpec::new(n, rows, chair)
                            };
                            shape::desk_rows(&t, &spec, seat, CHAIR_GAP_CM)
                                .ok()
                                .map(named)
                        } else {
                            // Long benches (pews) leave a centre aisle between the two of a
                            // row; other seats stand side by side.
                            let spacing = if seat.width >= crate::knowledge::LONG_BENCH_CM {
                                CENTRE_AISLE_CM
                            } else {
                                SEAT_SPACING_CM
                            };
                            let spec = RowsSpec {
                                first_row,
                                aisle,
                                spacing,
                                ..RowsSpec::new(n, rows, seat)
                            };
                            shape::rows(&t, &spec).ok().map(seats_only)
                        }
                    })
                    .collect()
            }
            (FormationShape::Pods, _) => {
                let pods = f.count.unwrap_or(n.div_ceil(4)).clamp(1, n);
                let spec = PodsSpec::new(pods, n.div_ceil(pods), seat, chair);
                let block =
                    |rotation: f64| shape::pods(DVec2::ZERO, rotation, &spec).ok().map(&named);
                return self.place_block(brief, draft, &block, 0.0).map(|p| (p, 0));
            }
            (FormationShape::Aisles, _) => {
                // The kind's own spacing (an exhibition's plinths), else shelving's.
                let spacing = self.knowledge.kind_of(first).spacing;
                let aisle = spacing.unwrap_or(AISLE_CM);
                let gap = spacing.unwrap_or(0.0);
                // As many lines as the count says, else those that make the block about as
                // deep as it is wide, then the others nearest that.
                let ideal = (n as f64 * (seat.width + gap) / (seat.depth + aisle / 2.0)).sqrt();
                let mut lines: Vec<usize> = (1..=n.min(MAX_AISLE_LINES)).collect();
                lines.sort_by(|a, b| {
                    (*a as f64 - ideal)
                        .abs()
                        .total_cmp(&(*b as f64 - ideal).abs())
                });
                if let Some(c) = f.count {
                    lines.insert(0, c.clamp(1, n));
                }
                for (variant, &k) in lines.iter().enumerate() {
                    let spec = AislesSpec {
                        aisle,
                        gap,
                        ..AislesSpec::new(n, k, seat)
                    };
                    let block = |rotation: f64| {
                        shape::aisles(DVec2::ZERO, rotation, &spec)
                            .ok()
                            .map(&seats_only)
                    };
                    if let Some(p) = self.place_block(brief, draft, &block, AISLE_END_CM) {
                        return Some((p, variant));
                    }
                }
                return None;
            }
            (FormationShape::OnePerMember | FormationShape::BehindEach, _) => {
                let of: Option<Vec<Footprint>> =
                    f.of.iter()
                        .map(|o| draft.where_is.get(o.as_str()).copied())
                        .collect();
                let of = of?;
                let each = of
                    .first()
                    .map(|o| Size::new(2.0 * o.half.x, 2.0 * o.half.y))?;
                let anchors: Vec<Pose> = of
                    .iter()
                    .map(|o| Pose {
                        center: o.center,
                        rotation: o.rotation,
                    })
                    .collect();
                let items = if f.shape == FormationShape::BehindEach {
                    shape::one_behind_each(&anchors, each, seat, STAND_DISTANCE_CM).ok()?
                } else {
                    shape::one_per_member(&anchors, each, seat, STAND_DISTANCE_CM).ok()?
                };
                vec![seats_only(items.into_iter().cycle().take(n).collect())]
            }
            (FormationShape::UTables, focus) => {
                super::letter::u_variants(brief, f, &members, focus)
            }
            (FormationShape::LDesks, _) => super::letter::l_variants(brief, f, &members),
            _ => Vec::new(),
        };
        let fitting = |poses: &HashMap<String, Pose>| {
            poses
                .iter()
                .filter(|(name, p)| asset(name).is_some_and(|a| draft.floor.fits_pose(p, a.size)))
                .count()
        };
        // Members that stay in the zone their focus stands in (not in an alcove the room's
        // other pieces are asked into).
        let zone = focus.and_then(|t| {
            brief
                .analysis
                .zones
                .iter()
                .find(|z| z.contains(t.center, 0.0))
        });
        let at_home = |poses: &HashMap<String, Pose>| {
            zone.map_or(0, |z| {
                poses.values().filter(|p| z.contains(p.center, 0.0)).count()
            })
        };
        // The variant where most fit, then most stay in the focus's zone; the first (the
        // shape's own defaults) among equals.
        variants
            .into_iter()
            .enumerate()
            .max_by_key(|(i, v)| (fitting(v), at_home(v), usize::MAX - i))
            .map(|(i, v)| (v, i))
    }

    /// A block of members (pods of desks, aisles of shelves) where the whole of it fits,
    /// nearest the main area's middle: `block` lays it out about the origin turned to a
    /// rotation (along the room's long side, or across it when only that fits). Each member
    /// keeps `margin` cm clear of the walls and of what stands already, all round.
    fn place_block(
        &self,
        brief: &GroupBrief<'_>,
        draft: &Draft<'_, '_>,
        block: &dyn Fn(f64) -> Option<HashMap<String, Pose>>,
        margin: f64,
    ) -> Option<HashMap<String, Pose>> {
        let aim = brief
            .analysis
            .zones
            .first()
            .map_or(brief.aim, |z| z.centre());
        let room = brief.room;
        let sizes: HashMap<&str, [f64; 3]> = brief
            .group
            .iter()
            .map(|a| {
                let [w, d, h] = a.size;
                (a.name.as_str(), [w + 2.0 * margin, d + 2.0 * margin, h])
            })
            .collect();
        let size_of = |name: &str| sizes.get(name).copied();
        let mut best: Option<(f64, HashMap<String, Pose>)> = None;
        for rotation in [0.0, 90.0] {
            let Some(poses) = block(rotation) else {
                continue;
            };
            let mut y = 0.0;
            while y <= room.depth {
                let mut x = 0.0;
                while x <= room.width {
                    let at = DVec2::new(x, y);
                    let d = at.distance(aim);
                    if best.as_ref().is_none_or(|(bd, _)| d < *bd) {
                        let fits = poses.iter().all(|(n, p)| {
                            size_of(n).is_some_and(|s| {
                                draft.floor.fits_pose(
                                    &Pose {
                                        center: p.center + at,
                                        rotation: p.rotation,
                                    },
                                    s,
                                )
                            })
                        });
                        if fits {
                            let moved = poses
                                .iter()
                                .map(|(n, p)| {
                                    (
                                        n.clone(),
                                        Pose {
                                            center: p.center + at,
                                            rotation: p.rotation,
                                        },
                                    )
                                })
                                .collect();
                            best = Some((d, moved));
                        }
                    }
                    x += POD_STEP_CM;
                }
                y += POD_STEP_CM;
            }
        }
        best.map(|(_, p)| p)
    }
}

/// The chairs `at` one desk, side by side along its front: the pose `p` the desk's one chair
/// would take, shifted so each of them has an equal share of the desk's `width`.
fn side_by_side(at: &[&Asset], p: &Pose, width: f64) -> Vec<(String, Pose)> {
    let m = at.len() as f64;
    let (sin, cos) = p.rotation.to_radians().sin_cos();
    let right = DVec2::new(cos, -sin);
    at.iter()
        .enumerate()
        .map(|(i, c)| {
            let x = (i as f64 - (m - 1.0) / 2.0) * width / m;
            (
                c.name.clone(),
                Pose {
                    center: p.center + right * x,
                    rotation: p.rotation,
                },
            )
        })
        .collect()
}
