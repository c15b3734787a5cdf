//! Which poses each object of a group may take, best first: a desk in a row its row seat, a
//! dependent the poses of its relation to its target, an anchor the best spots on a wall or the
//! open floor, a floor covering the middle of the room.

use glam::DVec2;

use super::agent::RuleDesigner;
use super::brief::{GroupBrief, dependents, gap};
use super::draft::Draft;
use super::free::{inside_main_door, place_flat, place_free, place_free_turned, place_in_corner};
use super::place::prefer_place;
use super::wall::place_on_wall;
use crate::arrangement::RunSlot;
use crate::knowledge::{Kind, words};
use disco_core::geometry::{Footprint, Wall};
use disco_core::layout::PlacedObject;
use disco_core::placement::{Pose, around_slots, relation_poses, wall_poses};
use disco_core::plan::{FormationShape, Relation};
use disco_core::scene::Asset;

/// How many more seats than chairs are laid out around a table, at most, to find free ones.
const EXTRA_SEATS_TRIED: usize = 6;

/// Spots within this many cm of each other, from the staff door, count as equally near it: the
/// designer's own order decides between them.
const STAFF_DOOR_BUCKET_CM: f64 = 200.0;

/// A counter worked from behind that the knowledge and the plan put nowhere in particular
/// stands by the room's staff door (a door other than the main one), where its staff come in:
/// `cands` the nearer to that door first, in buckets of [`STAFF_DOOR_BUCKET_CM`]; unchanged in
/// a room with one door.
fn towards_staff_door(brief: &GroupBrief<'_>, kind: &Kind, mut cands: Vec<Pose>) -> Vec<Pose> {
    let main = brief.analysis.main_door;
    let Some(door) = (0..brief.room.doors.len())
        .filter(|&i| Some(i) != main)
        .find_map(|i| brief.room.door_middle(i))
    else {
        return cands;
    };
    if main.is_none() || !kind.places.is_empty() {
        return cands;
    }
    cands.sort_by_cached_key(|p| (p.center.distance(door) / STAFF_DOOR_BUCKET_CM) as i64);
    cands
}

/// Floor (cm) kept behind the seats round a free-standing anchor, for a person to walk to
/// them: the reach check's walkway.
const BEHIND_SEATS_CM: f64 = 40.0;

impl RuleDesigner {
    /// Candidate poses for `asset`, best first. `target` is its first relation in the plan with
    /// where that target stands, when it is placed already. A member of a formation takes its
    /// place in the formation first.
    pub(super) fn candidates(
        &self,
        brief: &GroupBrief<'_>,
        draft: &mut Draft<'_, '_>,
        asset: &Asset,
        target: Option<(Relation, &str, Footprint)>,
    ) -> Vec<Pose> {
        let in_formation = self.formation_pose(brief, draft, asset);
        let mut cands: Vec<Pose> = in_formation.into_iter().collect();
        cands.extend(self.own_candidates(brief, draft, asset, target));
        cands
    }

    /// [`candidates`](Self::candidates) by the object's own kind and relations.
    fn own_candidates(
        &self,
        brief: &GroupBrief<'_>,
        draft: &mut Draft<'_, '_>,
        asset: &Asset,
        target: Option<(Relation, &str, Footprint)>,
    ) -> Vec<Pose> {
        let kind = self.knowledge.kind_of(asset);
        let c = brief.plan.constraints.get(&asset.name);
        let [w, d, _] = asset.size;
        if let Some(seat) = draft.rows.get(&asset.name) {
            let mut cands = vec![*seat];
            cands.extend(place_free(draft.floor, asset.size, kind.clearance, 0.0));
            return cands;
        }
        match target {
            // A floor covering the plan ties to a piece lies under it.
            Some((_, t, tfp)) if asset.is_flat() => {
                let category = brief
                    .placed
                    .iter()
                    .chain(draft.out.iter())
                    .find(|o| o.name == t)
                    .map_or("", |o| o.category.as_str());
                let mut cands = vec![rug_under(&tfp, category, w, d)];
                cands.extend(place_free(draft.floor, asset.size, 0.0, 0.0));
                cands
            }
            Some((Relation::Around, t, tfp)) => seat_around(brief, draft, asset, &kind, t, &tfp),
            Some((rel, t, tfp)) => {
                let face = c.is_some_and(|c| c.facing.is_some());
                let mut cands = Vec::new();
                // Stock on a counter's staff side: on the wall across the staff's aisle, facing
                // the counter (the counter stood off that wall by the aisle and this depth).
                let on_wall = c.is_some_and(|c| c.against_wall);
                if rel == Relation::InFrontOf && on_wall {
                    cands.extend(self.stock_pose(brief, t, &tfp, d));
                }
                cands.extend(relation_poses(
                    w,
                    d,
                    rel,
                    &tfp,
                    brief.room,
                    gap(&kind),
                    face,
                ));
                // In a real room (an outline, doors, windows) a dependent whose relation finds
                // no free spot takes the open floor rather than a door's or a window's zone.
                let real_room = !brief.room.is_rectangle() || brief.room.has_openings();
                if real_room && !cands.iter().any(|p| draft.floor.fits_pose(p, asset.size)) {
                    // A piece beside something by a wall (a speaker beside the screen) keeps
                    // to the walls nearest it, not to the middle of the room.
                    if rel == Relation::SideOf && c.is_some_and(|c| c.against_wall) {
                        cands.extend(nearest_wall_spots(draft, asset, &tfp));
                    }
                    cands.extend(place_free(draft.floor, asset.size, kind.clearance, 0.0));
                }
                cands
            }
            None if asset.is_flat() => {
                // A rug lies under what people gather at (a coffee table, a dining table, the
                // foot of a bed), not alone on empty floor.
                let mut cands = rug_spots(brief, draft, w, d);
                if c.and_then(|c| c.place.as_ref())
                    .is_some_and(|p| p.by_entrance)
                {
                    cands.extend(inside_main_door(brief.room, brief.analysis, d));
                }
                cands.extend(place_flat(brief.room, w, d));
                self.in_place(brief, asset, cands)
            }
            None if c.is_some_and(|c| c.against_wall) => {
                // Stock behind a bar: facing the bar's back across the bartender's aisle.
                let behind = c
                    .and_then(|c| c.facing.as_deref())
                    .and_then(|t| draft.where_is.get(t).map(|fp| (t, *fp)))
                    .and_then(|(t, fp)| self.stock_pose(brief, t, &fp, d));
                let joined = self.join_run(brief, draft, &kind);
                let run = brief.runs.get(&asset.name).or(joined.as_ref());
                let mut cands: Vec<Pose> = behind.into_iter().collect();
                let mut on_wall =
                    place_on_wall(draft.floor, asset, &kind, brief.plan, brief.group, run);
                // A wall piece turned to something placed (the TV stand to the sofa) stands
                // across from it: the spots whose front looks at it first, in their order.
                let wished =
                    brief.in_corner.contains(&asset.name) || brief.by_window.contains(&asset.name);
                if let Some(fp) = c
                    .and_then(|c| c.facing.as_deref())
                    .and_then(|t| draft.where_is.get(t))
                    .filter(|_| !wished)
                {
                    on_wall.sort_by_cached_key(|p| {
                        Footprint::new(p.center, w, d, p.rotation)
                            .front_ray_hit(fp)
                            .is_none()
                    });
                }
                cands.extend(on_wall);
                self.in_place(brief, asset, cands)
            }
            None if kind.staff > 0.0 && !brief.centre.contains(&asset.name) => {
                // A counter with a staff side: placed on a wall as if it were as deep as the
                // counter and the staff's aisle together, then moved off the wall by that
                // aisle. The staff side faces the wall: a bar's back (its stools are at its
                // front), any other counter's front (docs/formats.md: the front is where the
                // person who works at it stands or sits).
                // What stands on the staff side against the wall facing it (stock shelves)
                // widens the aisle by its depth.
                let stock = brief
                    .group
                    .iter()
                    .filter(|a| {
                        brief.plan.constraints.get(&a.name).is_some_and(|c| {
                            c.against_wall && c.facing.as_deref() == Some(asset.name.as_str())
                        })
                    })
                    .map(|a| a.size[1])
                    .fold(0.0, f64::max);
                let aisle = kind.staff + stock;
                let deep = Asset::new(&asset.name, &asset.category, [w, d + aisle, asset.size[2]]);
                let turn = if kind.staff_behind() { 0.0 } else { 180.0 };
                let cands = place_on_wall(draft.floor, &deep, &kind, brief.plan, brief.group, None)
                    .into_iter()
                    .map(|p| Pose {
                        center: p.center
                            + Footprint::new(p.center, w, d, p.rotation).front * (aisle / 2.0),
                        rotation: p.rotation + turn,
                    })
                    .collect();
                let cands = towards_staff_door(brief, &kind, cands);
                self.in_place(brief, asset, cands)
            }
            None => {
                // Room for the chairs around it.
                let ring = dependents(brief.plan, brief.group, Relation::Around, &asset.name)
                    .map(|a| a.size[1] + gap(&self.knowledge.kind_of(a)))
                    .fold(0.0, f64::max);
                let mut cands = Vec::new();
                if brief.in_corner.contains(&asset.name) {
                    cands = place_in_corner(brief.room, w, d, ring);
                }
                // Asked into a zone: turned along the zone's own long side first.
                let zone = c
                    .and_then(|c| c.place.as_ref())
                    .and_then(|p| p.zone.as_deref());
                if let Some(z) = zone.and_then(|z| brief.analysis.zones_named(z).first().copied()) {
                    let along_x = z.max[0] - z.min[0] >= z.max[1] - z.min[1];
                    let rotation = if along_x == (w >= d) { 0.0 } else { 90.0 };
                    // Its front to the rest of the room (an altar in its apse, a piano in
                    // its bay): the main area is what it faces.
                    let main = brief.analysis.zones.first().map(|m| m.centre());
                    let turned =
                        place_free_turned(draft.floor, asset.size, kind.clearance, ring, rotation)
                            .into_iter()
                            .map(|p| match main {
                                Some(m)
                                    if Footprint::new(p.center, w, d, p.rotation)
                                        .front
                                        .dot(m - p.center)
                                        < 0.0 =>
                                {
                                    Pose {
                                        center: p.center,
                                        rotation: p.rotation + 180.0,
                                    }
                                }
                                _ => p,
                            });
                    cands.extend(turned);
                }
                cands.extend(place_free(draft.floor, asset.size, kind.clearance, ring));
                // Where the plan puts it, its seats still need their floor and a way to them
                // from behind: a table seated down its long sides only keeps its ends free to
                // touch a wall.
                let per_side_only = brief.plan.formations.iter().any(|f| {
                    f.shape == FormationShape::PerSide
                        && f.focus.as_deref() == Some(asset.name.as_str())
                        && f.count.is_some_and(|n| f.members.len() <= 2 * n)
                });
                let sides = ring + BEHIND_SEATS_CM;
                let ends = if per_side_only { 0.0 } else { sides };
                let seats_fit = |p: &Pose| {
                    ring == 0.0
                        || draft.floor.fits(
                            &Footprint::new(p.center, w + 2.0 * ends, d + 2.0 * sides, p.rotation),
                            asset.size[2],
                        )
                };
                self.in_place_fitting(brief, asset, cands, &seats_fit)
            }
        }
    }

    /// An anchor's candidates, those where the plan puts it in the room first (see
    /// [`prefer_place`]); unchanged when the plan puts it nowhere in particular.
    fn in_place(&self, brief: &GroupBrief<'_>, asset: &Asset, cands: Vec<Pose>) -> Vec<Pose> {
        self.in_place_fitting(brief, asset, cands, &|_| true)
    }

    /// [`Self::in_place`], the poses where `fits` holds (its seats have room) first among those
    /// that honour the place equally.
    fn in_place_fitting(
        &self,
        brief: &GroupBrief<'_>,
        asset: &Asset,
        cands: Vec<Pose>,
        fits: &dyn Fn(&Pose) -> bool,
    ) -> Vec<Pose> {
        let cands = towards_door_window(brief, asset, cands);
        match brief
            .plan
            .constraints
            .get(&asset.name)
            .and_then(|c| c.place.as_ref())
        {
            Some(place) if !place.is_empty() => {
                prefer_place(brief.room, brief.analysis, asset, place, cands, fits)
            }
            _ => keep_out_of_asked_zones(brief, asset, cands),
        }
    }
}

impl RuleDesigner {
    /// Where stock `d` cm deep stands for the counter `counter` (at `fp`) when that counter has a
    /// staff side: on the wall across the staff's aisle, facing the counter (its front, or a
    /// bar's back). `None` when `counter` is no counter of the group.
    fn stock_pose(
        &self,
        brief: &GroupBrief<'_>,
        counter: &str,
        fp: &Footprint,
        d: f64,
    ) -> Option<Pose> {
        let kind = brief
            .group
            .iter()
            .find(|a| a.name == counter)
            .map(|a| self.knowledge.kind_of(a))
            .filter(|k| k.staff > 0.0)?;
        let (side, rotation) = if kind.staff_behind() {
            (-fp.front, fp.rotation)
        } else {
            (fp.front, fp.rotation + 180.0)
        };
        Some(Pose {
            center: fp.center + side * (fp.half.y + kind.staff + d / 2.0),
            rotation,
        })
    }

    /// The run a wall piece of `kind` joins when its kind names one (a kitchen's work pieces):
    /// any wall, packed towards the piece of that run placed last, so the run grows as a chain.
    /// `None` for the first piece, and for kinds of no run.
    fn join_run(
        &self,
        brief: &GroupBrief<'_>,
        draft: &Draft<'_, '_>,
        kind: &Kind,
    ) -> Option<RunSlot> {
        let run = kind.run.as_deref()?;
        let last = draft
            .out
            .iter()
            .rev()
            .chain(brief.placed.iter().rev())
            .find(|o| {
                self.knowledge
                    .lookup_text(&o.category)
                    .or_else(|| self.knowledge.lookup_text(&o.name))
                    .is_some_and(|k| k.run.as_deref() == Some(run))
            })?;
        Some(RunSlot {
            walls: Wall::all(brief.room),
            towards: DVec2::from(last.position),
            joined: true,
        })
    }
}

/// What a floor covering lies under, by category words, first found first.
const RUG_UNDER: [&str; 5] = ["coffee table", "dining table", "table", "sofa", "bed"];

/// Poses for a floor covering of `w` x `d` under the first piece of [`RUG_UNDER`] placed so far
/// (centred on a table, towards the front of a sofa or a bed), its long side along the piece's.
fn rug_spots(brief: &GroupBrief<'_>, draft: &Draft<'_, '_>, w: f64, d: f64) -> Vec<Pose> {
    let placed = || brief.placed.iter().chain(draft.out.iter());
    let Some(piece) = RUG_UNDER.iter().find_map(|word| {
        placed()
            .filter(|o| !o.is_flat() && words(&o.category).contains(word))
            .max_by(|a, b| (a.size[0] * a.size[1]).total_cmp(&(b.size[0] * b.size[1])))
    }) else {
        return Vec::new();
    };
    vec![rug_under(&piece.footprint(), &piece.category, w, d)]
}

/// The pose of a floor covering of `w` x `d` under the piece standing at `fp`: centred on a
/// table, towards the front of a seat or a bed, its long side along the piece's.
fn rug_under(fp: &Footprint, category: &str, w: f64, d: f64) -> Pose {
    let along_width = (fp.half.x >= fp.half.y) == (w >= d);
    let rotation = if along_width {
        fp.rotation
    } else {
        fp.rotation + 90.0
    };
    // A table stands on the rug's middle; a seat or a bed on the rug's back part.
    let out = if words(category).contains("table") || category.is_empty() {
        0.0
    } else {
        fp.half.y + d.min(w) / 2.0 - fp.half.y.min(40.0)
    };
    Pose {
        center: fp.center + fp.front * out,
        rotation: disco_core::geometry::normalize_degrees(rotation),
    }
}

/// `slots` round the table at `tfp`, those at its ends (farthest along its long side) first.
fn ends_first(tfp: &Footprint, mut slots: Vec<Pose>) -> Vec<Pose> {
    let long = if tfp.half.x >= tfp.half.y {
        tfp.front.perp()
    } else {
        tfp.front
    };
    slots.sort_by(|a, b| {
        let along = |p: &Pose| (p.center - tfp.center).dot(long).abs();
        along(b).total_cmp(&along(a))
    });
    slots
}

/// Poses for a chair around table `t` (standing at `tfp`): the table's next free seat, then the
/// relation's own poses. The table's seats are laid out the first time one is asked for, as many
/// as the group has chairs around it, in a circle when the table is round.
fn seat_around(
    brief: &GroupBrief<'_>,
    draft: &mut Draft<'_, '_>,
    asset: &Asset,
    kind: &Kind,
    t: &str,
    tfp: &Footprint,
) -> Vec<Pose> {
    let [w, d, _] = asset.size;
    if !draft.seats.contains_key(t) {
        let n = dependents(brief.plan, brief.group, Relation::Around, t).count();
        let round = brief
            .placed
            .iter()
            .chain(draft.out.iter())
            .find(|o| o.name == t)
            .is_some_and(is_round);
        // Seats a wall or a neighbour takes are no seats: lay out more until `n` are free (a
        // table against a wall seats its chairs on its open sides).
        let floor = &*draft.floor;
        let free = |m: usize| -> Vec<Pose> {
            around_slots(tfp, round, w, d, m, gap(kind))
                .into_iter()
                .filter(|p| floor.fits_pose(p, asset.size))
                .collect()
        };
        // A table set before a seat (a coffee table before the sofa) keeps its far side open
        // (towards what the sofa faces): its other seats take its ends first.
        let before_a_seat = brief.plan.constraints.get(t).is_some_and(|c| {
            c.relations
                .iter()
                .any(|r| r.relation == Relation::InFrontOf)
        });
        let at_ends = (before_a_seat && !round)
            .then(|| {
                (n..=n + EXTRA_SEATS_TRIED)
                    .map(|m| free(m.max(4)))
                    .find(|s| s.len() >= n)
            })
            .flatten()
            .map(|slots| ends_first(tfp, slots).into_iter().take(n).collect());
        let seats: Vec<Pose> = at_ends.unwrap_or_else(|| {
            let seats = around_slots(tfp, round, w, d, n, gap(kind));
            let fitting = seats
                .iter()
                .filter(|p| floor.fits_pose(p, asset.size))
                .count();
            match (n..=n + EXTRA_SEATS_TRIED)
                .map(free)
                .find(|s| s.len() >= n)
                .filter(|s| s.len() > fitting)
            {
                Some(enough) => enough.into_iter().take(n).collect(),
                None => seats,
            }
        });
        draft
            .seats
            .insert(t.to_string(), seats.into_iter().rev().collect());
    }
    let list = draft.seats.entry(t.to_string()).or_default();
    let seat = list.pop();
    let mut cands: Vec<Pose> = seat.into_iter().collect();
    cands.extend(relation_poses(
        w,
        d,
        Relation::Around,
        tfp,
        brief.room,
        gap(kind),
        true,
    ));
    cands
}

/// Whether a table is round: by its category, or by a square top.
fn is_round(o: &PlacedObject) -> bool {
    words(&o.category).contains("round") || (o.size[0] - o.size[1]).abs() < 1.0
}

/// Spots with `asset`'s back on a wall where it fits, nearest `near` first.
fn nearest_wall_spots(draft: &Draft<'_, '_>, asset: &Asset, near: &Footprint) -> Vec<Pose> {
    let [w, d, h] = asset.size;
    let mut spots: Vec<Pose> = wall_poses(draft.floor.room, w, d, h, NEAR_WALL_STEP_CM)
        .into_iter()
        .map(|(_, p)| p)
        .filter(|p| draft.floor.fits_pose(p, asset.size))
        .collect();
    spots.sort_by(|a, b| {
        a.center
            .distance(near.center)
            .total_cmp(&b.center.distance(near.center))
    });
    spots.truncate(NEAR_WALL_SPOTS);
    spots
}

/// Step (cm) along the walls of the search for a spot near a piece.
const NEAR_WALL_STEP_CM: f64 = 10.0;

/// Most wall spots near a piece offered.
const NEAR_WALL_SPOTS: usize = 8;

/// `cands` of a piece the plan puts nowhere in particular, those outside every zone the plan
/// asks other pieces into first ("the armchairs in the snug to the left": the bar counter
/// stands elsewhere), in their order otherwise. A zone no piece is asked into is no one's.
fn keep_out_of_asked_zones(brief: &GroupBrief<'_>, asset: &Asset, cands: Vec<Pose>) -> Vec<Pose> {
    let zones: Vec<&str> = brief
        .plan
        .constraints
        .iter()
        .filter(|(name, _)| **name != asset.name)
        .filter_map(|(_, c)| c.place.as_ref()?.zone.as_deref())
        .filter(|z| *z != "main")
        .collect();
    if zones.is_empty() {
        return cands;
    }
    let asked: Vec<&disco_core::room::analysis::Zone> = zones
        .iter()
        .flat_map(|z| brief.analysis.zones_named(z))
        .collect();
    let mut keyed: Vec<(bool, Pose)> = cands
        .into_iter()
        .map(|p| (asked.iter().any(|z| z.contains(p.center, 0.0)), p))
        .collect();
    keyed.sort_by_key(|(inside, _)| *inside);
    keyed.into_iter().map(|(_, p)| p).collect()
}

/// `cands` of a piece the prompt wants at the window nearest the main door, nearest that
/// window's middle first; the others as they are. Ranking by the place after this keeps the
/// order among spots that honour it equally (under either window).
fn towards_door_window(brief: &GroupBrief<'_>, asset: &Asset, mut cands: Vec<Pose>) -> Vec<Pose> {
    if !brief.window_by_door.contains(&asset.name) {
        return cands;
    }
    let room = brief.room;
    let Some(door) = brief.analysis.main_door.and_then(|i| room.door_middle(i)) else {
        return cands;
    };
    let Some(window) = room
        .windows
        .iter()
        .filter_map(|w| room.opening_ends(w.wall, w.at, w.width))
        .map(|(a, b)| (a + b) / 2.0)
        .min_by(|a, b| a.distance(door).total_cmp(&b.distance(door)))
    else {
        return cands;
    };
    let [w, d, _] = asset.size;
    cands.sort_by_cached_key(|p| {
        let back = Footprint::new(p.center, w, d, p.rotation).back_center();
        (back.distance(window) / 10.0).round() as i64
    });
    cands
}
