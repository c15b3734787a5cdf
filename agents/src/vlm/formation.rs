//! Formations on the model path: the model designs what a formation is arranged about (the
//! piano of an arc, the table of seats per side), and the formation's members are posed by the
//! shape's exact function, as the rules designer poses them (`RuleDesigner::design_group`,
//! which lays formations out with `disco_tools::formation`). The ties a formation makes (a
//! chair of the arc facing the piano) are the shape's, so they are neither asked piece by piece
//! nor refined piece by piece: the loop moves a formation only as a whole, with its focus.

use disco_core::layout::PlacedObject;
use disco_core::plan::{Formation, FormationShape, Plan};
use disco_core::scene::{Asset, SceneSpec};

use crate::rules::RuleDesigner;

/// The desk a chair comes with, when `name`'s first relation names a member of a formation of
/// rows or pods (whose desks bring their chairs, posed with them).
pub fn formation_chair<'p>(plan: &'p Plan, name: &str) -> Option<&'p str> {
    let first = plan.constraints.get(name)?.relations.first()?;
    plan.formation_of(&first.target)
        .filter(|f| matches!(f.shape, FormationShape::Rows | FormationShape::Pods))
        .map(|_| first.target.as_str())
}

/// Whether `name` is posed by a formation's shape: a member, or the chair of a desk of rows or
/// pods.
pub fn posed_by_formation(plan: &Plan, name: &str) -> bool {
    plan.formation_of(name).is_some() || formation_chair(plan, name).is_some()
}

/// Whether `subject`'s relation (or facing) to `target` is one its formation settles: `target`
/// is the formation's focus or another member, or `subject` is the chair of desk `target` in
/// rows or pods. Such a tie is posed exactly by the shape.
pub fn formation_settles(plan: &Plan, subject: &str, target: &str) -> bool {
    if let Some(f) = plan.formation_of(subject) {
        return f.focus.as_deref() == Some(target) || f.members.iter().any(|m| m == target);
    }
    formation_chair(plan, subject) == Some(target)
}

/// The formation whose focus is `name`, if any (the formations `name` carries along when it
/// moves).
pub fn formations_about<'p>(plan: &'p Plan, name: &str) -> Vec<&'p Formation> {
    plan.formations
        .iter()
        .filter(|f| f.focus.as_deref() == Some(name))
        .collect()
}

/// A formation in words, for the designer's request: `an arc of chair-0, chair-1 (50 x 50 cm
/// each) about piano-0`.
pub fn describe_formation(scene: &SceneSpec, f: &Formation) -> String {
    let shape = match f.shape {
        FormationShape::Rows => "rows",
        FormationShape::Arc => "an arc",
        FormationShape::Ring => "a ring",
        FormationShape::PerSide => "seats down each long side",
        FormationShape::AlongFront => "a line along the front",
        FormationShape::Pods => "pods of desks",
        FormationShape::OnePerMember => "one in front of each",
        FormationShape::BehindEach => "one behind each",
        FormationShape::Aisles => "parallel lines with aisles",
        FormationShape::UTables => "tables in a U with seats round the outside",
        FormationShape::LDesks => "two desks in an L with the chair in the crook",
    };
    let size = f
        .members
        .first()
        .and_then(|m| scene.asset(m))
        .map(|a| {
            format!(
                " ({} x {} cm each)",
                a.size[0].round() as i64,
                a.size[1].round() as i64
            )
        })
        .unwrap_or_default();
    let about = match (&f.focus, f.of.is_empty()) {
        (Some(focus), _) => format!(" about {focus}"),
        (None, false) => format!(" of {}", f.of.join(", ")),
        (None, true) => String::new(),
    };
    format!("{shape} of {}{size}{about}", f.members.join(", "))
}

/// Poses `members` (objects of the group that [`posed_by_formation`]) by their formations'
/// exact shapes about what `placed` holds (the model's poses of the focus included), as the
/// rules designer does; a member whose focus does not stand yet gets the rules designer's pose.
pub fn pose_members(
    scene: &SceneSpec,
    plan: &Plan,
    members: &[&Asset],
    placed: &[PlacedObject],
) -> Vec<PlacedObject> {
    if members.is_empty() {
        return Vec::new();
    }
    RuleDesigner::new().design_group(scene, plan, members, placed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use disco_core::plan::{ObjectConstraints, Relation, RelationSpec};

    fn plan_with_arc() -> Plan {
        let mut plan = Plan::default();
        plan.formations.push(Formation {
            shape: FormationShape::Arc,
            focus: Some("piano-0".into()),
            members: vec!["chair-0".into(), "chair-1".into()],
            count: None,
            of: Vec::new(),
        });
        plan.formations.push(Formation {
            shape: FormationShape::Rows,
            focus: Some("board-0".into()),
            members: vec!["desk-0".into()],
            count: Some(1),
            of: Vec::new(),
        });
        plan.constraints.insert(
            "stool-0".into(),
            ObjectConstraints {
                relations: vec![RelationSpec {
                    relation: Relation::InFrontOf,
                    target: "desk-0".into(),
                }],
                ..Default::default()
            },
        );
        plan
    }

    #[test]
    fn a_formation_settles_its_own_ties_and_no_others() {
        let plan = plan_with_arc();
        assert!(formation_settles(&plan, "chair-0", "piano-0"));
        assert!(formation_settles(&plan, "chair-0", "chair-1"));
        assert!(!formation_settles(&plan, "chair-0", "lamp-0"));
        // The chair of a desk in rows comes with the desk.
        assert!(formation_settles(&plan, "stool-0", "desk-0"));
        assert!(!formation_settles(&plan, "piano-0", "chair-0"));
        assert!(posed_by_formation(&plan, "stool-0"));
        assert!(!posed_by_formation(&plan, "piano-0"));
        assert_eq!(formations_about(&plan, "piano-0").len(), 1);
    }
}
