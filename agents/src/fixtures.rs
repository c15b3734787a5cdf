//! Test fixtures the agents' tests share: a rectangular room of named assets, and a plan of
//! pieces off the floor.

use disco_core::plan::{ObjectConstraints, Plan, Relation, RelationSpec};
use disco_core::scene::{Asset, Room, SceneSpec, Support};

/// A 500 x 400 cm room holding `items` (name, category, size), with no prompt.
pub(crate) fn scene(items: &[(&str, &str, [f64; 3])]) -> SceneSpec {
    SceneSpec {
        id: "t".into(),
        prompt: String::new(),
        room_type: "room".into(),
        room: Room::rect(500.0, 400.0),
        assets: items.iter().map(|(n, c, s)| Asset::new(n, c, *s)).collect(),
    }
}

/// A piece off the floor: its name, what holds it, and its relation to what holds it.
pub(crate) type Holding<'a> = (&'a str, Support, Option<(Relation, &'a str)>);

/// A plan of pieces off the floor, each with its support and relation.
pub(crate) fn plan_holding(entries: &[Holding<'_>]) -> Plan {
    let mut plan = Plan::default();
    for (name, support, rel) in entries {
        plan.constraints.insert(
            name.to_string(),
            ObjectConstraints {
                support: Some(*support),
                relations: rel
                    .iter()
                    .map(|(r, t)| RelationSpec {
                        relation: *r,
                        target: t.to_string(),
                    })
                    .collect(),
                ..Default::default()
            },
        );
    }
    plan
}
