//! Plain placement hints read from the scene's prompt: "a table in the center", "a plant in a
//! corner", "bookshelves along the walls", "a sofa facing the TV", "a lamp next to the sofa",
//! "chairs around the table", "an island surrounded by stools", "two sofas facing each other",
//! "a desk by the window", "a lamp on each nightstand", "the painting above the sofa".
//!
//! A hint names the objects by their category (or a synonym from the furniture knowledge, singular
//! or plural) and applies to every asset of that category. The rule planner turns hints into plan
//! constraints; the rule designer uses the spots (centre, corner) the plan vocabulary cannot say.

use crate::knowledge::{Knowledge, words};
use disco_core::plan::{FormationShape, Place, Relation, WallRole};
use disco_core::scene::SceneSpec;

/// Where the prompt wants an object.
#[derive(Debug, Clone, PartialEq)]
pub enum Hint {
    /// In the middle of the room, free-standing.
    Centre,
    /// In a corner, back on a wall.
    Corner,
    /// Back on a wall.
    AlongWall,
    /// Back on a wall, as near a window as it may stand ("a desk by the window").
    ByWindow,
    /// In the middle of the wall it is put on ("the sideboard against the far wall, centred on
    /// it", "in the middle of the back wall").
    CentredOnWall,
    /// At the window nearest the main door, of several ("under the window nearest the door").
    WindowByDoor,
    /// Turned towards the target objects.
    Facing(Vec<usize>),
    /// In this relation to one of the target objects.
    Relation(Relation, Vec<usize>),
    /// Across from the first of its kind, the two facing each other ("two sofas facing each
    /// other").
    FacingEachOther(usize),
    /// Where in the room, by its parts: a zone, a wall's role, the far corner, under a window,
    /// by the entrance ("the desk in the alcove", "the bed against the wall opposite the door").
    Place(Place),
    /// Arranged together in a shape ("six chairs in a semicircle facing the piano").
    Formation(FormationHint),
    /// Behind the targets: a seat behind a desk, counter or easel sits at its working side; any
    /// other piece stands near the target ("a floor lamp behind the armchair").
    Behind(Vec<usize>),
    /// Between the targets ("the coffee table between them"): near them, the knowledge's own
    /// place kept when it is by one of them.
    Between(Vec<usize>),
    /// Under the targets: a rug under a table; a console under the TV on the wall (the TV
    /// hangs over it, as the mounting rules already hang it); else near them.
    Under(Vec<usize>),
}

/// A formation the prompt asks of the mentioned assets.
#[derive(Debug, Clone, PartialEq)]
pub struct FormationHint {
    /// The shape.
    pub shape: FormationShape,
    /// Rows, pods or seats per side, when the prompt counts them.
    pub count: Option<usize>,
    /// What the formation faces or surrounds (assets), when the prompt names it.
    pub focus: Vec<usize>,
    /// For one per member: the assets each member stands before.
    pub of: Vec<usize>,
    /// Rows that face a wall with nothing of the room's on it ("facing the whiteboard on the
    /// left wall" when the scene lists no whiteboard): that wall, by its role.
    pub wall: Option<WallRole>,
}

/// One hint: the assets (indices into the scene's assets) it is about, and what it says.
#[derive(Debug, Clone, PartialEq)]
pub struct PromptHint {
    /// The assets the hint is about.
    pub subjects: Vec<usize>,
    /// What it says about them.
    pub hint: Hint,
}

/// A run of prompt words naming some assets.
#[derive(Debug, Clone)]
struct Mention {
    start: usize,
    end: usize,
    assets: Vec<usize>,
    /// "it" or "them": only ever a target, never the subject of a hint.
    pronoun: bool,
}

/// Words skipped between a mention and the phrase that follows it.
const FILLER: [&str; 26] = [
    "the", "a", "an", "is", "are", "placed", "set", "standing", "stands", "sits", "arranged",
    "grouped", "tucked", "goes", "go", "sit", "stand", "should", "can", "will", "must", "be",
    "spaced", "laid", "pushed", "lives",
];

/// The hints in `scene.prompt`, in the order they appear.
///
/// The assets' own descriptions come first, each read as a sentence about its asset (see
/// [`described_hints`]); the prompt's hints follow and, read later, win where they disagree.
pub fn read_hints(scene: &SceneSpec, knowledge: &Knowledge) -> Vec<PromptHint> {
    let (mut out, prompt) = read_hints_apart(scene, knowledge);
    out.extend(prompt);
    out
}

/// [`read_hints`] in its two parts: what the descriptions say ([`described_hints`]), then what
/// the prompt says, for a reader that weighs them apart (the rule planner lets no description
/// take a seat from what it serves).
pub fn read_hints_apart(
    scene: &SceneSpec,
    knowledge: &Knowledge,
) -> (Vec<PromptHint>, Vec<PromptHint>) {
    let tokens = prompt_tokens(&scene.prompt);
    let mentions = find_mentions(scene, knowledge, &tokens);
    let mut prompt = reading_corner(scene, knowledge, &tokens, &mentions);
    prompt.extend(fronted_places(&tokens, &mentions));
    for m_index in 0..mentions.len() {
        if !mentions[m_index].pronoun {
            prompt.extend(mention_hints(&tokens, &mentions, m_index));
        }
    }
    join_single_rows(&mut prompt);
    drop_restated_formations(&mut prompt);
    prompt.retain(names_others);
    let mut described = described_hints(scene, knowledge);
    described.retain(names_others);
    (described, prompt)
}

/// The targets a hint names, for the hints that name any.
fn targets(hint: &Hint) -> Option<&[usize]> {
    match hint {
        Hint::Facing(t)
        | Hint::Relation(_, t)
        | Hint::Behind(t)
        | Hint::Between(t)
        | Hint::Under(t) => Some(t),
        _ => None,
    }
}

/// Whether `h` names targets, if it is a kind that does, other than its own subjects.
fn names_others(h: &PromptHint) -> bool {
    targets(&h.hint).is_none_or(|t| !t.is_empty() && t != h.subjects.as_slice())
}

/// The hints the assets' descriptions give, each read with the prompt's grammar as a sentence
/// whose subject is its asset: "hemodialysis machine: beside a dialysis chair" reads as "the
/// hemodialysis machine beside a dialysis chair", "instrument table: in the niche" as a place.
///
/// Object lists written by a language model describe the first of a run of alike pieces
/// ("recliner seat: in three rows of six facing the screen", then seventeen more recliners,
/// one of them "second row"): a description's hints hold for its asset and for the assets of
/// its category after it, up to the next one whose own description gives other hints (a
/// description repeated word for word continues the run). A
/// description that says nothing of where its piece goes gives nothing, and is not reported
/// as unread (it may only say what the piece is).
pub fn described_hints(scene: &SceneSpec, knowledge: &Knowledge) -> Vec<PromptHint> {
    let described = |j: usize| scene.assets[j].description.as_deref();
    let category = |j: usize| scene.assets[j].category.as_str();
    // Pieces described word for word alike ("one behind each teller counter", three times)
    // are one run, read once: the first of them.
    let first_alike: Vec<usize> = (0..scene.assets.len())
        .map(|i| {
            (0..i)
                .find(|&j| category(j) == category(i) && described(j) == described(i))
                .unwrap_or(i)
        })
        .collect();
    let mut own: Vec<Vec<PromptHint>> = Vec::with_capacity(scene.assets.len());
    for (i, &first) in first_alike.iter().enumerate() {
        let hints = match first {
            j if j == i => description_hints(scene, knowledge, i),
            // Only whether it asks anything matters for a repeat.
            j => own[j].clone(),
        };
        own.push(hints);
    }
    let mut out = Vec::new();
    for (i, hints) in own.iter().enumerate() {
        let alike = |j: usize| category(j) == category(i);
        if hints.is_empty() || first_alike[i] != i {
            continue;
        }
        let run: Vec<usize> = std::iter::once(i)
            .chain(
                (i + 1..scene.assets.len())
                    .filter(|&j| alike(j))
                    .take_while(|&j| own[j].is_empty() || described(j) == described(i)),
            )
            .collect();
        out.extend(hints.iter().map(|h| PromptHint {
            subjects: if h.subjects == [i] {
                run.clone()
            } else {
                h.subjects.clone()
            },
            hint: h.hint.clone(),
        }));
    }
    out
}

/// The hints asset `i`'s own description gives about it, read as "<its category> <its
/// description>" with the category naming `i` alone.
fn description_hints(scene: &SceneSpec, knowledge: &Knowledge, i: usize) -> Vec<PromptHint> {
    let asset = &scene.assets[i];
    let Some(description) = asset
        .description
        .as_deref()
        .filter(|d| !d.trim().is_empty())
    else {
        return Vec::new();
    };
    let subject = prompt_tokens(&asset.category);
    let said = prompt_tokens(description);
    // The description as it stands, then from each word that may open a place ("technician
    // sits at the footbath in front of a pedicure chair": from "in front of"), the first
    // reading that gives a hint.
    let starts = std::iter::once(0).chain((1..said.len()).filter(|&k| {
        WHERE_WORDS.contains(&said[k].as_str()) || OPENS_PLACE.contains(&said[k].as_str())
    }));
    for k in starts {
        let mut tokens = subject.clone();
        tokens.extend(said[k..].iter().cloned());
        let hints = subject_hints(scene, knowledge, i, &tokens, subject.len());
        if !hints.is_empty() {
            return hints;
        }
    }
    Vec::new()
}

/// Words that open a place in a description but say none by themselves ("in", "on", "next").
const OPENS_PLACE: [&str; 5] = ["in", "on", "next", "by", "at"];

/// The hints `tokens` give about asset `i`, whose category is its first `subject_len` words.
fn subject_hints(
    scene: &SceneSpec,
    knowledge: &Knowledge,
    i: usize,
    tokens: &[String],
    subject_len: usize,
) -> Vec<PromptHint> {
    let mut mentions: Vec<Mention> = find_mentions(scene, knowledge, tokens)
        .into_iter()
        .filter(|m| m.start >= subject_len)
        .collect();
    mentions.insert(
        0,
        Mention {
            start: 0,
            end: subject_len,
            assets: vec![i],
            pronoun: false,
        },
    );
    let mut out = fronted_places(tokens, &mentions);
    out.extend(mention_hints(tokens, &mentions, 0));
    out.retain(|h| {
        h.subjects == [i] && targets(&h.hint).is_none_or(|t| !t.is_empty() && !t.contains(&i))
    });
    out
}

/// Words that say where something goes. A mention followed by one of them, in its own clause,
/// asks for a placement; when no hint comes of it, the words were not understood.
const WHERE_WORDS: [&str; 47] = [
    "against",
    "facing",
    "face",
    "faces",
    "beside",
    "opposite",
    "across",
    "near",
    "under",
    "beneath",
    "below",
    "around",
    "behind",
    "between",
    "along",
    "front",
    "row",
    "rows",
    "circle",
    "semicircle",
    "arc",
    "ring",
    "corner",
    "wall",
    "walls",
    "window",
    "windows",
    "centre",
    "center",
    "middle",
    "side",
    "sides",
    "flanking",
    "flanked",
    "flank",
    "back",
    "left",
    "right",
    "alcove",
    "nook",
    "bay",
    "arm",
    "wing",
    "end",
    "entrance",
    "door",
    "diagonal",
];

/// The parts of the prompt that ask where something goes but gave no hint: a mention whose own
/// words (up to the next mention, within its clause) hold a placement word, and from which no
/// hint came. Each is quoted as written (lower case), for the run's notes ("not understood:
/// ..."), so nothing the user asked is dropped silently.
pub fn unread_phrases(scene: &SceneSpec, knowledge: &Knowledge) -> Vec<String> {
    let tokens = prompt_tokens(&scene.prompt);
    let mentions = find_mentions(scene, knowledge, &tokens);
    let corner = reading_corner(scene, knowledge, &tokens, &mentions);
    let hinted: Vec<bool> = (0..mentions.len())
        .map(|k| !mention_hints(&tokens, &mentions, k).is_empty())
        .collect();
    let formed: Vec<PromptHint> = read_hints(scene, knowledge)
        .into_iter()
        .filter(|h| matches!(&h.hint, Hint::Formation(f) if matches!(f.shape, FormationShape::Ring | FormationShape::Arc)))
        .collect();
    let mut out: Vec<String> = Vec::new();
    for (k, m) in mentions.iter().enumerate() {
        // A target of the mention before it was read with that mention ("the sofa facing the
        // TV": the TV's words are the sofa's).
        let read_before = k > 0
            && hinted[k - 1]
            && !tokens[mentions[k - 1].end..m.start]
                .iter()
                .any(|w| w == CLAUSE_END || w == SENTENCE_END);
        let end = mentions.get(k + 1).map_or(tokens.len(), |n| n.start);
        let own: Vec<&str> = tokens[m.end..end]
            .iter()
            .map(String::as_str)
            .take_while(|w| *w != CLAUSE_END && *w != SENTENCE_END)
            .collect();
        let asks = own.iter().any(|w| WHERE_WORDS.contains(w));
        let in_corner = corner
            .iter()
            .any(|h| m.assets.iter().any(|a| h.subjects.contains(a)));
        // "Every chair facing the centre" of chairs a ring or an arc turns to its middle.
        let turned_in = faces_inward(&own) && in_ring_or_arc(&formed, &m.assets);
        if m.pronoun
            || hinted[k]
            || !asks
            || in_corner
            || turned_in
            || (read_before && own.is_empty())
        {
            continue;
        }
        let through = if own.len() == end - m.end {
            mentions.get(k + 1).map_or(end, |n| n.end)
        } else {
            m.end + own.len()
        };
        let phrase = tokens[m.start..through].join(" ");
        if !out.contains(&phrase) {
            out.push(phrase);
        }
    }
    out
}

/// Places said before what they hold: "In the left wing two sofas face each other ...", "Turn
/// the short arm of the L into a reading corner: an armchair, a lamp ...". The words from a
/// sentence's start to its first mention name a place; it holds every mention up to the
/// sentence's end.
fn fronted_places(tokens: &[String], mentions: &[Mention]) -> Vec<PromptHint> {
    let mut out = Vec::new();
    let mut start = 0;
    while start < tokens.len() {
        let end = tokens[start..]
            .iter()
            .position(|w| w == SENTENCE_END)
            .map_or(tokens.len(), |i| start + i);
        // A piece the place is told by ("in the snug to the left of the bar") is no piece put
        // there.
        let in_place_words = |m: &Mention| {
            m.start >= start + 2
                && tokens[m.start - 1] == "the"
                && matches!(tokens[m.start - 2].as_str(), "of" | "from")
        };
        let mut inside: Vec<&Mention> = mentions
            .iter()
            .filter(|m| !m.pronoun && m.start >= start && m.end <= end)
            .collect();
        while inside.first().is_some_and(|m| {
            in_place_words(m) && !tokens[start..m.start].iter().any(|w| w == CLAUSE_END)
        }) {
            inside.remove(0);
        }
        if let Some(first) = inside.first() {
            let lead: Vec<&str> = tokens[start..first.start]
                .iter()
                .map(String::as_str)
                .filter(|w| *w != CLAUSE_END)
                .collect();
            // A place, not a description of the room ("a bedroom with one angled wall: ...").
            let locative = lead.first().is_some_and(|w| {
                matches!(
                    *w,
                    "in" | "into"
                        | "inside"
                        | "within"
                        | "along"
                        | "against"
                        | "on"
                        | "at"
                        | "by"
                        | "under"
                        | "beneath"
                        | "near"
                        | "beside"
                )
            }) || lead.contains(&"into");
            // "Make a reading corner in the short arm of the L with the bookcase, the two
            // beanbags and the rug": a place, then "with" the pieces that go there.
            let with_at = lead
                .iter()
                .rposition(|w| !matches!(*w, "the" | "a" | "an" | "its" | "their"))
                .filter(|&k| lead[k] == "with");
            let lead = match with_at {
                Some(k) if !locative => lead[..k]
                    .iter()
                    .position(|w| matches!(*w, "in" | "into" | "inside" | "within"))
                    .map_or(Vec::new(), |from| lead[from..k].to_vec()),
                _ => lead,
            };
            if (locative || with_at.is_some())
                && let Some(place) = place_in_room(&lead)
            {
                // "Along the window wall, two bistro tables with two chairs each": the wall is
                // the tables'; their chairs sit at them.
                let at_wall = place.wall.is_some() || place.under_window;
                out.push(PromptHint {
                    subjects: inside
                        .iter()
                        .filter(|m| !(at_wall && is_companion(tokens, m)))
                        .flat_map(|m| m.assets.iter().copied())
                        .collect(),
                    hint: Hint::Place(place),
                });
            }
        }
        start = end + 1;
    }
    out
}

/// "Facing the centre", "facing in", "turned inwards": words that only say a piece looks to
/// the middle of what it stands round.
fn faces_inward(own: &[&str]) -> bool {
    own.windows(2).any(|w| {
        matches!(w[0], "facing" | "face" | "faces" | "turned")
            && matches!(w[1], "in" | "inward" | "inwards" | "the")
    }) && own.iter().all(|w| {
        matches!(
            *w,
            "facing"
                | "face"
                | "faces"
                | "turned"
                | "in"
                | "inward"
                | "inwards"
                | "the"
                | "centre"
                | "center"
                | "middle"
                | "all"
                | "every"
                | "each"
        )
    }) && own.iter().any(|w| {
        matches!(
            *w,
            "in" | "inward" | "inwards" | "centre" | "center" | "middle"
        )
    })
}

/// True when every one of `assets` is in a ring or an arc of `formed`.
fn in_ring_or_arc(formed: &[PromptHint], assets: &[usize]) -> bool {
    !assets.is_empty()
        && assets
            .iter()
            .all(|a| formed.iter().any(|h| h.subjects.contains(a)))
}

/// The prompt as lower-case words. Punctuation that ends a clause stays as a `,` token (a place
/// named after it is not the earlier clause's), a sentence's end as `;`.
fn prompt_tokens(prompt: &str) -> Vec<String> {
    let spaced: String = prompt
        .to_lowercase()
        .chars()
        .map(|c| match c {
            ',' | ':' | '(' | ')' => '|',
            ';' | '.' | '!' | '?' => '#',
            c => c,
        })
        .collect::<String>()
        .replace('|', " , ")
        .replace('#', " ; ");
    spaced
        .split(|c: char| !(c.is_alphanumeric() || c == '\'' || c == ',' || c == ';'))
        .filter(|w| !w.is_empty())
        // "the bed's headboard": the possessive names the bed.
        .map(|w| w.strip_suffix("'s").unwrap_or(w).to_string())
        .collect()
}

/// The hints the words around mention `m_index` give: a place before or after it, a relation to
/// the next mention, "facing each other", "surrounded by".
fn mention_hints(tokens: &[String], mentions: &[Mention], m_index: usize) -> Vec<PromptHint> {
    let m = &mentions[m_index];
    let mut out = Vec::new();
    // "central X".
    if m.start > 0
        && matches!(
            tokens[m.start - 1].as_str(),
            "central" | "centre" | "center"
        )
    {
        out.push(hint(m, Hint::Centre));
    }
    let after = skip_filler(tokens, m.end);
    let rest: Vec<&str> = tokens[after..].iter().map(String::as_str).collect();
    let next = mentions.get(m_index + 1).filter(|n| n.start >= after);
    let phrase = |p: &[&str]| rest.len() >= p.len() && rest[..p.len()] == *p;
    let then_target = |len: usize| next.filter(|n| skip_filler(tokens, after + len) == n.start);
    // "The writing desk and its chair under the window": the window is the desk's; the chair
    // sits at the desk, off the wall (the place below covers the desk).
    let joined_companion = owned_companion(tokens, m)
        && m_index > 0
        && tokens[mentions[m_index - 1].end..m.start]
            .iter()
            .all(|w| LINKS.contains(&w.as_str()));
    // "Near the front window": the window's own word tells no place.
    let plain_rest = plain_openings(&rest);
    let plain_phrase = |p: &[&str]| plain_rest.len() >= p.len() && plain_rest[..p.len()] == *p;
    // "In the middle of the back wall", "centred on it": the middle of a wall, not the room's.
    // Its own words only, up to the next piece named ("the sofa faces the TV in the middle of
    // the back wall": the TV's).
    let own_rest = &rest[..next
        .map_or(rest.len(), |n| n.start.saturating_sub(after))
        .min(rest.len())];
    let on_wall_middle = wall_middle(own_rest);
    if on_wall_middle {
        out.push(hint(m, Hint::CentredOnWall));
    }
    if window_by_door(own_rest) {
        out.push(hint(m, Hint::WindowByDoor));
    }
    if let Some(h) = place_hint(&plain_phrase).filter(|h| {
        let companion_s =
            joined_companion && matches!(h, Hint::ByWindow | Hint::AlongWall | Hint::Corner);
        let wall_s = on_wall_middle && *h == Hint::Centre;
        !(companion_s || wall_s)
    }) {
        out.push(hint(m, h));
    }
    // The words up to the next mention (at most a clause's length) may say where in the room.
    let clause_end = mentions
        .get(m_index + 1)
        .map_or(tokens.len(), |n| n.start)
        .max(m.end);
    let clause = own_clause(&tokens[m.end..clause_end]);
    // Its words up to the next piece named, within the sentence.
    let to_next: Vec<&str> = tokens[m.end..clause_end]
        .iter()
        .map(String::as_str)
        .take_while(|w| *w != SENTENCE_END)
        .collect();
    // "Two armchairs opposite each other in the middle of the room": the middle anywhere in
    // the mention's own words.
    let centre_said = clause
        .windows(3)
        .any(|w| w[0] == "in" && w[1] == "the" && matches!(w[2], "middle" | "centre" | "center"));
    if centre_said
        && !on_wall_middle
        && !out.iter().any(|h| h.hint == Hint::Centre)
        && place_hint(&plain_phrase).is_none()
    {
        out.push(hint(m, Hint::Centre));
    }
    let formation = formation_hint(tokens, mentions, m_index, &clause)
        .or_else(|| letter_formation_hint(tokens, mentions, m_index, &clause));
    let formed = formation.is_some();
    // "a nightstand on each side (of the bed)", "lamps on either side": beside the piece named
    // next, else the one named before in the sentence.
    if formation.is_none()
        && let Some(len) = [
            &["on", "each", "side"][..],
            &["on", "either", "side"],
            &["on", "both", "sides"],
            &["either", "side"],
            &["each", "side"],
        ]
        .iter()
        .find(|p| phrase(p))
        .map(|p| p.len())
    {
        let of = usize::from(rest.get(len) == Some(&"of"));
        let target = then_target(len + of)
            .map(|t| t.assets.clone())
            .or_else(|| previous_in_sentence(tokens, mentions, m_index));
        if let Some(t) = target {
            out.push(hint(m, Hint::Relation(Relation::SideOf, t)));
        }
    }
    // "The piano with its bench in front": before the piece named before, when no target
    // follows.
    if phrase(&["in", "front"])
        && rest
            .get(2)
            .is_none_or(|w| *w == CLAUSE_END || *w == SENTENCE_END || *w == "and")
        && let Some(t) = previous_in_sentence(tokens, mentions, m_index)
    {
        out.push(hint(m, Hint::Relation(Relation::InFrontOf, t)));
    }
    if let Some(f) = formation {
        out.push(hint(m, Hint::Formation(f)));
    }
    if let Some(place) = place_in_room(&clause) {
        // "an armchair with a floor lamp and a side table in the short arm": the place is the
        // whole party's, back to the first mention the linking words reach.
        let mut first = m_index;
        // A companion ("the desk with its chair, the wardrobe against the angled wall", "each
        // with a chair, the wardrobe on the right") is its piece's, not the next clause's.
        let companion = |k: usize| is_companion(tokens, &mentions[k]);
        let owned = |k: usize| owned_companion(tokens, &mentions[k]);
        while first > 0
            && !mentions[first - 1].pronoun
            && tokens[mentions[first - 1].end..mentions[first].start]
                .iter()
                .all(|w| LINKS.contains(&w.as_str()))
            && !(companion(first - 1)
                && tokens[mentions[first - 1].end..mentions[first].start]
                    .iter()
                    .any(|w| w == CLAUSE_END))
        {
            first -= 1;
        }
        // A wall or a window a piece and its companion are put at is the piece's ("the
        // writing desk and its chair under the window"): the chair sits at the desk, off the
        // wall; a zone is both's ("the round table and its two chairs in the bay").
        let at_wall = place.wall.is_some() || place.under_window;
        out.push(PromptHint {
            subjects: (first..=m_index)
                .filter(|&k| !(at_wall && k > first && owned(k)))
                .flat_map(|k| mentions[k].assets.iter().copied())
                .collect(),
            hint: Hint::Place(place),
        });
    }
    // "Four chairs on each side of the table" is a formation, not a pair beside it.
    if let Some(h) = relation_hint(&phrase, &then_target)
        .filter(|h| !(formed && matches!(h, Hint::Relation(Relation::SideOf, _))))
    {
        out.push(hint(m, h));
    }
    out.extend(
        end_and_side_hints(&phrase, &then_target, &|| {
            previous_in_sentence(tokens, mentions, m_index)
        })
        .map(|h| hint(m, h)),
    );
    // "two armchairs facing each other across the coffee table": both at it.
    for p in [
        &["facing", "each", "other", "across"][..],
        &["face", "each", "other", "across"],
        &["opposite", "each", "other", "across"],
    ] {
        if phrase(p)
            && let Some(t) = then_target(p.len())
        {
            out.push(hint(m, Hint::Relation(Relation::Around, t.assets.clone())));
        }
    }
    // "two sofas facing each other": the others across from the first.
    if ([
        &["facing", "each", "other"][..],
        &["face", "each", "other"],
        &["opposite", "each", "other"],
        &["across", "from", "each", "other"],
    ]
    .iter()
    .any(|p| phrase(p))
        || own_words_face_each_other(&to_next))
        && m.assets.len() >= 2
    {
        out.push(PromptHint {
            subjects: m.assets[1..].to_vec(),
            hint: Hint::FacingEachOther(m.assets[0]),
        });
    }
    // "The two mats side by side", "both beds go ... side by side": the others beside the
    // first.
    if m.assets.len() >= 2
        && clause
            .windows(3)
            .any(|w| w[0] == "side" && w[1] == "by" && w[2] == "side")
        && !formed
    {
        out.push(PromptHint {
            subjects: m.assets[1..].to_vec(),
            hint: Hint::Relation(Relation::SideOf, vec![m.assets[0]]),
        });
    }
    // "X surrounded by Y": Y around X.
    if phrase(&["surrounded", "by"])
        && let Some(t) = then_target(2)
    {
        out.push(PromptHint {
            subjects: t.assets.clone(),
            hint: Hint::Relation(Relation::Around, m.assets.clone()),
        });
    }
    out
}

/// Relations named by a piece's end, foot or back, and "between": "a side table at the left
/// end of the sofa", "a bench across its foot", "two chairs behind the counter", "the table
/// between them". With no target after the words ("at its foot"), the piece named before.
fn end_and_side_hints<'m>(
    phrase: &dyn Fn(&[&str]) -> bool,
    then_target: &dyn Fn(usize) -> Option<&'m Mention>,
    previous: &dyn Fn() -> Option<Vec<usize>>,
) -> Option<Hint> {
    let target = |len: usize| then_target(len).map(|t| t.assets.clone());
    let foot: [&[&str]; 6] = [
        &["at", "the", "foot", "of"],
        &["across", "the", "foot", "of"],
        &["at", "its", "foot"],
        &["across", "its", "foot"],
        &["at", "the", "foot"],
        &["across", "the", "foot"],
    ];
    if let Some(p) = foot.iter().find(|p| phrase(p)) {
        let t = target(p.len()).or_else(previous)?;
        return Some(Hint::Relation(Relation::InFrontOf, t));
    }
    let end: [&[&str]; 8] = [
        &["at", "the", "ends", "of"],
        &["at", "both", "ends", "of"],
        &["at", "each", "end", "of"],
        &["at", "either", "end", "of"],
        &["at", "one", "end", "of"],
        &["at", "the", "left", "end", "of"],
        &["at", "the", "right", "end", "of"],
        &["at", "the", "end", "of"],
    ];
    if let Some(p) = end.iter().find(|p| phrase(p)) {
        return Some(Hint::Relation(Relation::SideOf, target(p.len())?));
    }
    // "The table with a chair at each end": the ends of the piece named before.
    if [
        &["at", "each", "end"][..],
        &["at", "either", "end"],
        &["at", "both", "ends"],
    ]
    .iter()
    .any(|p| phrase(p))
    {
        return Some(Hint::Relation(Relation::SideOf, previous()?));
    }
    for p in [&["behind"][..], &["just", "behind"], &["right", "behind"]] {
        if phrase(p) {
            return Some(Hint::Behind(target(p.len()).or_else(previous)?));
        }
    }
    if phrase(&["between"]) {
        return Some(Hint::Between(target(1)?));
    }
    // "With the side table in between them" (a pronoun, read as the mention it names).
    if phrase(&["in", "between"]) {
        return Some(Hint::Between(target(2)?));
    }
    for p in [&["under"][..], &["beneath"], &["below"], &["underneath"]] {
        if phrase(p) {
            return Some(Hint::Under(target(p.len())?));
        }
    }
    None
}

/// The assets of the mention before `m_index` in the same sentence (a pronoun's included).
fn previous_in_sentence(
    tokens: &[String],
    mentions: &[Mention],
    m_index: usize,
) -> Option<Vec<usize>> {
    let m = &mentions[m_index];
    m_index
        .checked_sub(1)
        .map(|k| &mentions[k])
        .filter(|p| !tokens[p.end..m.start].iter().any(|w| w == SENTENCE_END))
        .map(|p| p.assets.clone())
}

/// A place named right after a mention: "in the centre/middle", "free", "in a corner", "along
/// (against, on) the wall", "by (near, under, at, beside, next to, in front of) the window".
fn place_hint(phrase: &dyn Fn(&[&str]) -> bool) -> Option<Hint> {
    let by_window = |words: &[&str]| {
        ["window", "windows"].iter().any(|w| {
            let mut p = words.to_vec();
            p.extend(["the", w]);
            phrase(&p)
        })
    };
    if phrase(&["in", "the", "center"])
        || phrase(&["in", "the", "centre"])
        || phrase(&["in", "the", "middle"])
        // "the bed stands free (in the centre of the room)".
        || phrase(&["free"])
    {
        Some(Hint::Centre)
    } else if phrase(&["in", "a", "corner"])
        || phrase(&["in", "the", "corner"])
        || phrase(&["into", "a", "corner"])
        || phrase(&["into", "the", "corner"])
    {
        Some(Hint::Corner)
    } else if phrase(&["along", "the", "wall"])
        || phrase(&["along", "the", "walls"])
        || phrase(&["against", "the", "wall"])
        || phrase(&["on", "the", "wall"])
    {
        Some(Hint::AlongWall)
    } else if [
        &["by"][..],
        &["near"],
        &["under"],
        &["at"],
        &["beside"],
        &["next", "to"],
        &["in", "front", "of"],
    ]
    .iter()
    .any(|w| by_window(w))
        || [
            &["either", "side", "of"][..],
            &["on", "either", "side", "of"],
            &["each", "side", "of"],
            &["on", "each", "side", "of"],
        ]
        .iter()
        .any(|w| by_window(w))
    {
        Some(Hint::ByWindow)
    } else {
        None
    }
}

/// True when `m` is named as another piece's own: "its chair", "their lamps", "its own stool".
fn owned_companion(tokens: &[String], m: &Mention) -> bool {
    let word = |back: usize| m.start.checked_sub(back).map(|k| tokens[k].as_str());
    matches!(word(1), Some("its" | "their"))
        || (word(1) == Some("own") && matches!(word(2), Some("its" | "their")))
}

/// True when `m` is named as another piece's companion: owned ("its chair") or brought along
/// ("each with a chair", "with two stools").
fn is_companion(tokens: &[String], m: &Mention) -> bool {
    let word = |back: usize| m.start.checked_sub(back).map(|k| tokens[k].as_str());
    owned_companion(tokens, m)
        || word(1) == Some("with")
        || (word(1).is_some_and(|w| matches!(w, "a" | "an") || count_word(w).is_some())
            && word(2) == Some("with"))
}

/// Whether the words after a mention, up to its sentence's end or the next piece, put it in
/// the middle of a wall: "in the middle (centre) of the back wall", "centred on it (the wall)".
fn wall_middle(rest: &[&str]) -> bool {
    let end = rest
        .iter()
        .position(|w| *w == SENTENCE_END)
        .unwrap_or(rest.len());
    let words = &rest[..end.min(CLAUSE_WORDS * 2)];
    words.iter().enumerate().any(|(i, w)| match *w {
        "middle" | "centre" | "center" => {
            words.get(i + 1) == Some(&"of")
                && words[i + 2..]
                    .iter()
                    .take(4)
                    .take_while(|w| **w != CLAUSE_END)
                    .any(|w| *w == "wall")
        }
        "centred" | "centered" => {
            // "Centred on it" (the wall just named), "centred on the far wall"; not "centred
            // on the sofa".
            words.get(i + 1) == Some(&"on")
                && (words.get(i + 2) == Some(&"it")
                    || words[(i + 2).min(words.len())..]
                        .iter()
                        .take(4)
                        .any(|w| *w == "wall"))
        }
        _ => false,
    })
}

/// Whether the words after a mention, up to its clause's end, name the window nearest the
/// door: "under the window nearest the door", "by the window closest to the entrance".
fn window_by_door(rest: &[&str]) -> bool {
    let end = rest
        .iter()
        .position(|w| *w == SENTENCE_END || *w == CLAUSE_END)
        .unwrap_or(rest.len());
    let words = &rest[..end.min(CLAUSE_WORDS)];
    words.iter().enumerate().any(|(i, w)| {
        matches!(*w, "window" | "windows")
            && words[i + 1..]
                .iter()
                .take(2)
                .any(|n| matches!(*n, "nearest" | "closest" | "next" | "by"))
            && words[i + 1..]
                .iter()
                .take(5)
                .any(|n| matches!(*n, "door" | "entrance" | "entry"))
    })
}

/// Whether a mention's own words turn its pieces to each other further on: "in the bay, turned
/// to face each other".
fn own_words_face_each_other(clause: &[&str]) -> bool {
    clause
        .windows(3)
        .any(|w| matches!(w[0], "face" | "facing") && w[1] == "each" && w[2] == "other")
        && !clause.contains(&"across")
}

/// Most words of an aside between commas a mention's place is read past ("edges touching").
const ASIDE_WORDS: usize = 3;

/// Words that open a place phrase ("by the wall", "at the front").
const PLACE_WORDS: [&str; 11] = [
    "at", "by", "against", "along", "on", "near", "in", "into", "under", "beside", "inside",
];

/// A mention's own words, `after` it (up to the next mention): up to the clause's end, or past one comma when a place
/// phrase goes on after another ("the instructor's mat at the front, by the wall opposite the
/// entrance") or says its wall again.
fn own_clause(after: &[String]) -> Vec<&str> {
    let words: Vec<&str> = after.iter().map(String::as_str).collect();
    // Each part at most a clause's length.
    let end = |from: usize| {
        let from = from.min(words.len());
        words[from..]
            .iter()
            .position(|w| *w == CLAUSE_END || *w == SENTENCE_END)
            .map_or(words.len(), |k| from + k)
            .min(from + CLAUSE_WORDS)
    };
    let first = end(0);
    // "On the back wall, the long wall opposite the shop window": the wall said again.
    let wall_again = words.get(first + 1) == Some(&"the")
        && words[first + 1..].iter().take(4).any(|w| *w == "wall");
    let second = end(first + 1);
    // "The two trestle tables, which should sit against the entrance wall": the piece's own
    // clause, said after a comma.
    let relative = first == 0
        && words.get(first) == Some(&CLAUSE_END)
        && words
            .get(first + 1)
            .is_some_and(|w| matches!(*w, "which" | "that" | "both" | "each"));
    let goes_on = (words[..first].iter().any(|w| PLACE_WORDS.contains(w))
        && words.get(first) == Some(&CLAUSE_END)
        && (words
            .get(first + 1)
            .is_some_and(|w| PLACE_WORDS.contains(w))
            || wall_again))
        || relative;
    // "Side by side, edges touching, in the middle of the floor": past a short aside too.
    let past_aside = !goes_on
        && words.get(first) == Some(&CLAUSE_END)
        && second.saturating_sub(first + 1) <= ASIDE_WORDS
        && words.get(second) == Some(&CLAUSE_END)
        && words
            .get(second + 1)
            .is_some_and(|w| PLACE_WORDS.contains(w));
    if goes_on {
        let mut clause = words[..first].to_vec();
        clause.extend_from_slice(&words[first + 1..end(first + 1)]);
        clause
    } else if past_aside {
        let mut clause = words[..first].to_vec();
        clause.extend_from_slice(&words[second + 1..end(second + 1)]);
        clause
    } else {
        words[..first].to_vec()
    }
}

/// The token punctuation leaves between clauses.
const CLAUSE_END: &str = ",";

/// The token punctuation leaves between sentences (and `;`).
const SENTENCE_END: &str = ";";

/// Words that join mentions into one party ("an armchair with a lamp and a side table").
const LINKS: [&str; 12] = [
    "with", "and", "a", "an", "the", "its", "their", "plus", "two", "three", "four", CLAUSE_END,
];

/// A count word or number: "two", "4".
fn count_word(w: &str) -> Option<usize> {
    const WORDS: [&str; 13] = [
        "zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten",
        "eleven", "twelve",
    ];
    WORDS
        .iter()
        .position(|n| *n == w)
        .or_else(|| w.parse().ok().filter(|n| *n <= 1000))
}

/// How far (words) a formation's focus may follow its "facing".
const FOCUS_WORDS: usize = 25;

/// How far (words) it may follow when the words before "facing" point back to the members
/// ("all of them facing the altar").
const FAR_FOCUS_WORDS: usize = 40;

/// The formation the words around mention `m_index` ask for: "two rows of four desks ... facing
/// the whiteboard", "six chairs in a semicircle facing the piano", "two pods of four desks",
/// "four chairs on each long side", "stools along the front of the island", "a music stand in
/// front of each chair". `clause` is the mention's own words after it.
fn formation_hint(
    tokens: &[String],
    mentions: &[Mention],
    m_index: usize,
    clause: &[&str],
) -> Option<FormationHint> {
    let m = &mentions[m_index];
    let before = clause_before(tokens, m.start.saturating_sub(5), m.start);
    let text = format!(" {} ", clause.join(" "));
    let has = |p: &str| text.contains(&format!(" {p} "));
    // "N rows of", "N pods of": the count before the word.
    let counted = |nouns: &[&str]| -> Option<Option<usize>> {
        let i = before.iter().position(|w| nouns.contains(w))?;
        Some(i.checked_sub(1).and_then(|j| count_word(before[j])))
    };
    // The mention right after the clause, when the clause runs up to it.
    let next_in_clause = mentions
        .get(m_index + 1)
        .filter(|n| n.start == m.end + clause.len())
        .map(|n| n.assets.clone())
        .unwrap_or_default();
    // The first mention after "facing"/"towards" within the sentence.
    let faced = || -> Vec<usize> {
        let end = (m.end + FAR_FOCUS_WORDS).min(tokens.len());
        let stop = tokens[m.end..end]
            .iter()
            .position(|w| w == SENTENCE_END)
            .map_or(end, |i| m.end + i);
        // The piece named right after the word ("facing the board"), not any piece further
        // on ("facing the board on the left wall, two chairs at every desk"). Further than
        // `FOCUS_WORDS` on, only when the words point back ("..., all of them facing the
        // altar").
        let word = (m.end..stop).find(|&i| {
            matches!(tokens[i].as_str(), "facing" | "towards" | "toward" | "face")
                && (i < m.end + FOCUS_WORDS
                    || matches!(
                        tokens[i - 1].as_str(),
                        "them" | "all" | "also" | "both" | "each" | "every" | "too"
                    ))
        });
        word.and_then(|i| {
            let mut at = i + 1;
            while tokens.get(at).is_some_and(|w| {
                matches!(w.as_str(), "the" | "a" | "an" | "towards" | "toward" | "to")
            }) {
                at += 1;
            }
            mentions[m_index + 1..].iter().find(|n| n.start == at)
        })
        .map(|n| n.assets.clone())
        .unwrap_or_default()
    };
    // The mention before, in the same sentence: "the table ... with four chairs on each side".
    let previous =
        || -> Vec<usize> { previous_in_sentence(tokens, mentions, m_index).unwrap_or_default() };
    let or_previous = |v: Vec<usize>| if v.is_empty() { previous() } else { v };
    // The wall the words after "facing" name, up to the sentence's end ("facing the whiteboard
    // on the left wall", "facing the front wall").
    let faced_wall = || -> Option<WallRole> {
        let stop = tokens[m.end..]
            .iter()
            .position(|w| w == SENTENCE_END)
            .map_or(tokens.len(), |i| m.end + i);
        let from = (m.end..stop).find(|&i| matches!(tokens[i].as_str(), "facing" | "face"))?;
        let words: Vec<&str> = tokens[from..stop]
            .iter()
            .map(String::as_str)
            .take_while(|w| *w != CLAUSE_END)
            .collect();
        place_in_room(&words)?.wall
    };
    // The mention right after `word` in the sentence ("across the magazine table").
    let named_after = |word: &str| -> Vec<usize> {
        let stop = tokens[m.end..]
            .iter()
            .position(|w| w == SENTENCE_END)
            .map_or(tokens.len(), |i| m.end + i);
        (m.end..stop)
            .find(|&i| tokens[i] == word)
            .and_then(|i| {
                let at = skip_filler(tokens, i + 1);
                mentions[m_index + 1..].iter().find(|n| n.start == at)
            })
            .map(|n| n.assets.clone())
            .unwrap_or_default()
    };
    // "Two rows of four", the number in each row.
    let per_row = || -> Option<usize> {
        let i = before.iter().position(|w| matches!(*w, "rows" | "row"))?;
        (before.get(i + 1) == Some(&"of"))
            .then(|| before.get(i + 2).and_then(|w| count_word(w)))
            .flatten()
    };
    let across = named_after("across");
    let mut wall = None;
    let (shape, count, focus, of) = if let Some(n) =
        counted(&["rows", "row"]).or_else(|| counted_after(clause, &["rows", "row"]))
        && (has("facing each other") || has("face each other"))
        && !across.is_empty()
    {
        // Two rows facing each other across a table are the seats down its two long sides.
        let per = per_row().or_else(|| n.map(|rows| m.assets.len().div_ceil(rows.max(1))));
        (FormationShape::PerSide, per, across, Vec::new())
    } else if let Some(n) =
        counted(&["rows", "row"]).or_else(|| counted_after(clause, &["rows", "row"]))
    {
        let focus = faced();
        if focus.is_empty()
            && !has("back to back")
            && let Some(w) = faced_wall()
        {
            wall = Some(w);
            (FormationShape::Rows, n, focus, Vec::new())
        } else {
            rows_or_back_to_back(n, focus, has("back to back"))?
        }
    } else if let Some(rows) = counted_columns(&before, clause, m.assets.len()) {
        // "Eight pews in two columns of four": lines running towards the focus, four rows.
        rows_or_back_to_back(Some(rows), faced(), false)?
    } else if one_row_of_several(clause) {
        // "Three recliners in a front row ..., the other four in a back row behind them": one
        // row each, joined into one formation once every mention is read.
        rows_or_back_to_back(Some(1), faced(), false)?
    } else if let Some(n) = counted(&["pods", "pod", "clusters", "islands"])
        .or_else(|| counted_after(clause, &["pods", "pod", "clusters"]))
    {
        (FormationShape::Pods, n, Vec::new(), Vec::new())
    } else if [
        "semicircle",
        "semi circle",
        "half circle",
        "arc",
        "crescent",
        "half moon",
    ]
    .iter()
    .any(|p| has(p))
    {
        (FormationShape::Arc, None, next_in_clause, Vec::new())
    } else if has("back to back") {
        (FormationShape::Pods, None, Vec::new(), Vec::new())
    } else if [
        "each long side",
        "each side of the table",
        "both long sides",
        "either long side",
        "per side",
        "each long edge",
    ]
    .iter()
    .any(|p| has(p))
    {
        let per = before.iter().rev().find_map(|w| count_word(w));
        (
            FormationShape::PerSide,
            per,
            or_previous(next_in_clause),
            Vec::new(),
        )
    } else if has("along the front") || has("along its front") || has("along the front of") {
        (
            FormationShape::AlongFront,
            None,
            or_previous(next_in_clause),
            Vec::new(),
        )
    } else if has("in front of each") || has("before each") {
        // "A barber chair in front of each one": each of the pieces named before.
        let of = if next_in_clause.is_empty() && (has("each one") || has("each of them")) {
            previous()
        } else {
            next_in_clause
        };
        (FormationShape::OnePerMember, None, Vec::new(), of)
    } else if let Some(of) = behind_each(&before, clause, &next_in_clause) {
        (FormationShape::BehindEach, None, Vec::new(), of)
    } else if in_a_ring(clause) {
        (
            FormationShape::Ring,
            None,
            or_previous(next_in_clause),
            Vec::new(),
        )
    } else {
        return None;
    };
    // Rows named before the piece they face ("in a front row facing the screen") are not the
    // screen's.
    if shape == FormationShape::Rows
        && !focus.is_empty()
        && focus.iter().all(|f| m.assets.contains(f))
    {
        return None;
    }
    Some(FormationHint {
        shape,
        count,
        focus,
        of,
        wall,
    })
}

/// A U or an L the prompt asks the mention's pieces to form: "six tables in a U whose open end
/// faces the screen, two (chairs) per table", "tables arranged in a U", "a U-shaped table
/// layout facing the screen", "a horseshoe of tables" (a [`FormationShape::UTables`], its focus
/// the first piece named after "facing"/"faces"/"towards" in the sentence, its count the seats
/// "per table" or "at each table"); "an L-shaped desk in the corner", "two desks in an L" (a
/// [`FormationShape::LDesks`]). The planner decides whether the pieces can form it.
fn letter_formation_hint(
    tokens: &[String],
    mentions: &[Mention],
    m_index: usize,
    clause: &[&str],
) -> Option<FormationHint> {
    let m = &mentions[m_index];
    // The words before it, back to the mention before (whose own words they are beyond it).
    let from = m_index
        .checked_sub(1)
        .map_or(0, |k| mentions[k].end)
        .max(m.start.saturating_sub(4))
        .min(m.start);
    let before = clause_before(tokens, from, m.start);
    let text = format!(" {} ", clause.join(" "));
    let lead = format!(" {} ", before.join(" "));
    let after = |p: &str| text.contains(&format!(" {p} "));
    let ahead = |p: &str| lead.contains(&format!(" {p} "));
    let u = [
        "in a u",
        "into a u",
        "as a u",
        "u shape",
        "u shaped",
        "horseshoe",
    ]
    .iter()
    .any(|p| after(p))
        || ["u shape", "u shaped", "horseshoe of", "horseshoe"]
            .iter()
            .any(|p| ahead(p));
    // "A wine bar in an L-shaped unit": the room's shape, not the pieces'.
    let the_room = [
        "unit", "room", "space", "floor", "shop", "studio", "hall", "area", "plan",
    ]
    .iter()
    .any(|r| after(&format!("l shaped {r}")) || after(&format!("l shape {r}")));
    let l = !the_room
        && (["in an l", "into an l", "as an l", "l shape", "l shaped"]
            .iter()
            .any(|p| after(p))
            || ["l shape", "l shaped"].iter().any(|p| ahead(p)));
    // The sentence's words from the mention on.
    let stop = tokens[m.end..]
        .iter()
        .position(|w| w == SENTENCE_END)
        .map_or(tokens.len(), |i| m.end + i);
    if u {
        let focus = mentions[m_index + 1..]
            .iter()
            .find(|n| {
                n.start < stop.min(m.end + FOCUS_WORDS)
                    && tokens[m.end..n.start].iter().any(|w| {
                        matches!(
                            w.as_str(),
                            "facing" | "faces" | "face" | "towards" | "toward"
                        )
                    })
            })
            .map(|n| n.assets.clone())
            .unwrap_or_default();
        // "two per table", "two at each table", "two to a table".
        let rest: Vec<&str> = tokens[m.end..stop].iter().map(String::as_str).collect();
        let count = rest.windows(3).find_map(|w| {
            let per = matches!(
                (w[1], w[2]),
                ("per", _) | ("at", "each") | ("to", "a") | ("to", "each") | ("each", _)
            );
            count_word(w[0]).filter(|_| per)
        });
        return Some(FormationHint {
            shape: FormationShape::UTables,
            count,
            focus,
            of: Vec::new(),
            wall: None,
        });
    }
    l.then(|| FormationHint {
        shape: FormationShape::LDesks,
        count: None,
        focus: Vec::new(),
        of: Vec::new(),
        wall: None,
    })
}

/// "Desks in four rows (of two)": the count before a row word in the mention's own words
/// (always counted); `None` when no counted row word follows an "in".
fn counted_after(clause: &[&str], nouns: &[&str]) -> Option<Option<usize>> {
    let i = clause.iter().position(|w| nouns.contains(w))?;
    // Uncounted rows ("desks in rows facing the board") are the knowledge's to line up.
    let n = i.checked_sub(1).and_then(|j| count_word(clause[j]))?;
    clause[..i]
        .iter()
        .any(|w| matches!(*w, "in" | "into"))
        .then_some(Some(n))
}

/// The rows that "N columns of M" (before or after the mention) make of `total` pieces: M, or
/// the pieces per column when M is not said.
fn counted_columns(before: &[&str], clause: &[&str], total: usize) -> Option<usize> {
    let read = |words: &[&str]| -> Option<usize> {
        let i = words
            .iter()
            .position(|w| matches!(*w, "columns" | "column"))?;
        let columns = i.checked_sub(1).and_then(|j| count_word(words[j]))?;
        let per = (words.get(i + 1) == Some(&"of"))
            .then(|| words.get(i + 2).and_then(|w| count_word(w)))
            .flatten();
        Some(per.unwrap_or(total.div_ceil(columns.max(1))).max(1))
    };
    read(before).or_else(|| read(clause))
}

/// Whether the mention's words put it in one row of several: "in a front row", "in the back
/// row", "in a second row".
fn one_row_of_several(clause: &[&str]) -> bool {
    clause.windows(4).any(|w| {
        w[0] == "in"
            && matches!(w[1], "a" | "the")
            && matches!(
                w[2],
                "front" | "back" | "rear" | "first" | "second" | "third" | "last"
            )
            && w[3] == "row"
    })
}

/// Rows the prompt names one at a time ("three recliners in a front row facing the screen,
/// and the other four in a back row behind them") joined into one formation: consecutive
/// one-row formations of the same focus become its rows, in the order named.
fn join_single_rows(hints: &mut Vec<PromptHint>) {
    let single = |h: &PromptHint| matches!(&h.hint, Hint::Formation(f) if f.shape == FormationShape::Rows && f.count == Some(1));
    let focus = |h: &PromptHint| match &h.hint {
        Hint::Formation(f) => f.focus.clone(),
        _ => Vec::new(),
    };
    let mut k = 0;
    while k < hints.len() {
        if !single(&hints[k]) {
            k += 1;
            continue;
        }
        let mut rows = 1;
        while let Some(j) = (k + 1..hints.len())
            .find(|&j| single(&hints[j]) && focus(&hints[j]) == focus(&hints[k]))
        {
            let more = hints.remove(j).subjects;
            hints[k].subjects.extend(more);
            rows += 1;
        }
        if let Hint::Formation(f) = &mut hints[k].hint {
            f.count = Some(rows);
        }
        k += 1;
    }
}

/// "The eight student desks into two pods of four: in each pod two pairs of desks are pushed
/// together back to back": a formation of a shape said again of a wider mention (every desk,
/// the teacher's too) is the one read first, not a second one taking in more.
fn drop_restated_formations(hints: &mut Vec<PromptHint>) {
    let shape_of = |h: &PromptHint| match &h.hint {
        Hint::Formation(f) => Some(f.shape),
        _ => None,
    };
    let mut k = 0;
    while k < hints.len() {
        let restated = shape_of(&hints[k]).is_some_and(|shape| {
            hints[..k].iter().any(|e| {
                shape_of(e) == Some(shape)
                    && e.subjects.iter().all(|s| hints[k].subjects.contains(s))
            })
        });
        if restated {
            hints.remove(k);
        } else {
            k += 1;
        }
    }
}

/// A formation as read: shape, count, focus and the objects of one per member.
type ShapeRead = (FormationShape, Option<usize>, Vec<usize>, Vec<usize>);

/// Rows facing `focus`; rows "back to back" with nothing to face stand free as parallel lines,
/// their backs together and every front out ("two rows of four back to back in the middle"),
/// which is the aisles' block of `n` lines (two when uncounted). `None`: rows facing nothing
/// in the room (a board the scene lacks), which no formation can say; the words stay unread.
fn rows_or_back_to_back(
    n: Option<usize>,
    focus: Vec<usize>,
    back_to_back: bool,
) -> Option<ShapeRead> {
    if back_to_back && focus.is_empty() {
        Some((
            FormationShape::Aisles,
            Some(n.unwrap_or(2)),
            focus,
            Vec::new(),
        ))
    } else if focus.is_empty() {
        None
    } else {
        Some((FormationShape::Rows, n, focus, Vec::new()))
    }
}

/// "Each with a stool behind it", "a stool behind each easel": the objects (named right after
/// "behind") each member stands behind; `None` unless "behind" is said with "each" or "every".
fn behind_each(before: &[&str], clause: &[&str], next: &[usize]) -> Option<Vec<usize>> {
    let at = clause.iter().position(|w| *w == "behind")?;
    let each = |w: &&str| matches!(*w, "each" | "every");
    let counted = before.iter().any(each) || clause[at + 1..].iter().any(each);
    (counted && !next.is_empty()).then(|| next.to_vec())
}

/// "In a circle", "in a closed circle", "form a ring", "in a circular arrangement": a ring word
/// within three words after "in" or "form".
fn in_a_ring(clause: &[&str]) -> bool {
    clause.iter().enumerate().any(|(i, w)| {
        matches!(*w, "circle" | "ring" | "circular")
            && clause[i.saturating_sub(3)..i]
                .iter()
                .any(|b| matches!(*b, "in" | "form" | "forms" | "forming"))
            && !clause[..i].iter().any(|b| matches!(*b, "semi" | "half"))
    })
}

/// The words of `tokens[from..to]` after the last clause or sentence end among them: what
/// stands before a mention in its own clause.
fn clause_before(tokens: &[String], from: usize, to: usize) -> Vec<&str> {
    let words: Vec<&str> = tokens[from..to].iter().map(String::as_str).collect();
    match words
        .iter()
        .rposition(|w| *w == CLAUSE_END || *w == SENTENCE_END)
    {
        Some(i) => words[i + 1..].to_vec(),
        None => words,
    }
}

/// How many words after a mention may still say where in the room it goes.
const CLAUSE_WORDS: usize = 12;

/// Where in the room the words of a clause put its subject, by the room's parts: "in the
/// alcove", "in the short arm", "against the wall opposite the door", "on the wall without
/// windows", "on the left wall", "in the corner farthest from the door", "under the window",
/// "by the entrance". `None` when they name no part.
pub fn place_in_room(words: &[&str]) -> Option<Place> {
    let text = format!(" {} ", plain_openings(words).join(" "));
    let has = |p: &str| text.contains(&format!(" {p} "));
    let any = |ps: &[&str]| ps.iter().any(|p| has(p));
    let mut place = Place::default();
    // A zone: a word for a recess or a wing after "in"/"into", and the words between them
    // ("in the short arm": `short`).
    // "In the snug to the left": the side said after the noun counts as one said before it.
    let after_in = |nouns: &[&str]| -> Option<Vec<&str>> {
        (0..words.len()).find_map(|i| {
            if !matches!(words[i], "in" | "into" | "inside" | "within") {
                return None;
            }
            let k = words[i + 1..]
                .iter()
                .take(4)
                .position(|w| nouns.contains(w))?;
            let mut said = words[i + 1..i + 1 + k].to_vec();
            let noun = i + 1 + k;
            if let [to, the, side, ..] = words[(noun + 1).min(words.len())..]
                && matches!(to, "to" | "on")
                && the == "the"
                && matches!(side, "left" | "right")
            {
                said.push(side);
            }
            Some(said)
        })
    };
    // "Turn the short arm of the L into ...": an arm, wing or leg is a zone with or without "in".
    let the_part = || -> Option<Vec<&str>> {
        let k = words
            .iter()
            .position(|w| matches!(*w, "arm" | "wing" | "leg"))?;
        let from = words[..k].iter().rposition(|w| *w == "the")?;
        (k - from <= 3).then(|| words[from + 1..k].to_vec())
    };
    let part = after_in(&[
        "arm", "wing", "leg", "part", "section", "area", "end", "snug", "side", "bit",
    ])
    .or_else(the_part);
    let said = |ms: &[&str]| {
        part.as_ref()
            .is_some_and(|p| p.iter().any(|w| ms.contains(w)))
    };
    if after_in(&["alcove", "nook", "bay", "recess", "niche"]).is_some() {
        place.zone = Some("recess".into());
    } else if said(&[
        "wide", "main", "large", "big", "larger", "long", "central", "wider",
    ]) {
        place.zone = Some("main".into());
    } else if let Some(side) = ["left", "right", "top", "bottom"]
        .into_iter()
        .find(|side| said(&[side]))
    {
        // "In the left wing": the wing that lies that way on the plan.
        place.zone = Some(format!("wing-{side}"));
    } else if said(&[
        "short", "small", "narrow", "other", "side", "entry", "upper", "lower", "smaller",
        "second", "narrower", "shorter",
    ]) {
        place.zone = Some("wing".into());
    }
    // A wall by its role; the opening it is opposite, when named, before "the back wall".
    place.wall = if any(&[
        "opposite the door",
        "opposite the entrance",
        "across from the door",
        "across from the entrance",
        "facing the door",
        "facing the entrance",
    ]) {
        Some(WallRole::OppositeDoor)
    } else if any(&[
        "opposite the window",
        "opposite the windows",
        "opposite the bay",
        "across from the window",
        "across from the windows",
        "across from the bay",
    ]) {
        Some(WallRole::OppositeWindow)
    } else if any(&["far wall", "back wall", "far end", "rear wall"]) {
        Some(WallRole::OppositeDoor)
    } else if any(&[
        "door wall",
        "entrance wall",
        "wall with the door",
        "wall with the entrance",
        "wall of the door",
        "same wall as the door",
    ]) {
        Some(WallRole::Entrance)
    } else if any(&[
        "long windowless wall",
        "longest windowless wall",
        "long solid wall",
    ]) {
        Some(WallRole::LongestSolid)
    } else if any(&[
        "slanted wall",
        "angled wall",
        "diagonal wall",
        "sloping wall",
        "slanted corner",
        "angled corner",
        "slanted window wall",
        "slanted glass wall",
        "slanted glass",
    ]) {
        Some(WallRole::Slanted)
    } else if any(&[
        "left hand wall",
        "on your left",
        "left as you enter",
        "left as you come in",
        "left wall as you come in",
        "left wall as you enter",
        "left as you walk in",
        "to your left",
        "on your left when you walk in",
    ]) {
        Some(WallRole::LeftFromDoor)
    } else if any(&[
        "right hand wall",
        "on your right",
        "right as you enter",
        "right as you come in",
        "right wall as you come in",
        "right wall as you enter",
        "right as you walk in",
        "to your right",
        "on your right when you walk in",
    ]) {
        Some(WallRole::RightFromDoor)
    } else if any(&[
        "left wall",
        "left side wall",
        "long left wall",
        "left end wall",
        "wall to the left",
    ]) {
        Some(WallRole::Left)
    } else if any(&[
        "right wall",
        "right side wall",
        "long right wall",
        "right end wall",
        "wall to the right",
    ]) {
        Some(WallRole::Right)
    } else if any(&["top wall", "upper wall", "north wall"]) {
        Some(WallRole::Top)
    } else if any(&["bottom wall", "lower wall", "south wall"]) {
        Some(WallRole::Bottom)
    } else if any(&[
        "without windows",
        "without a window",
        "without any windows",
        "windowless",
        "with no window",
        "with no windows",
        "no windows",
        "solid wall",
        "blank wall",
    ]) {
        Some(WallRole::NoWindow)
    } else if any(&["long wall", "longest wall"]) {
        Some(WallRole::LongestSolid)
    } else if any(&[
        "window wall",
        "glass wall",
        "wall of windows",
        "wall with the windows",
    ]) {
        Some(WallRole::WithWindow)
    } else {
        None
    };
    place.far_corner = any(&[
        "farthest from the door",
        "furthest from the door",
        "farthest from the entrance",
        "furthest from the entrance",
        "far corner",
    ]);
    place.under_window = words.iter().enumerate().any(|(i, w)| {
        matches!(*w, "under" | "beneath" | "below" | "underneath")
            && words[i + 1..]
                .iter()
                .take(5)
                .any(|w| matches!(*w, "window" | "windows"))
    });
    place.by_entrance = !place.far_corner
        && place.wall.is_none()
        && any(&[
            "by the entrance",
            "near the entrance",
            "at the entrance",
            "beside the entrance",
            "next to the entrance",
            "by the door",
            "near the door",
            "beside the door",
            "next to the door",
            "by the entry",
            "near the entry",
            "close to the entrance",
            "close to the door",
            "close to the doors",
            "by the doors",
            "near the doors",
            "each side of the door",
            "either side of the door",
            "each side of the entrance",
            "either side of the entrance",
        ]);
    (!place.is_empty()).then_some(place)
}

/// `words` with the one word that tells a door or window apart dropped ("the main door",
/// "the shop window", "the back window"): the place is the same. A word that names a zone
/// stays ("the bay window").
fn plain_openings<'w>(words: &[&'w str]) -> Vec<&'w str> {
    const ZONE_WORDS: [&str; 5] = ["bay", "alcove", "nook", "recess", "niche"];
    let opening = |w: &str| matches!(w, "door" | "doors" | "window" | "windows" | "entrance");
    // "The sliding entrance doors": up to two words before the opening's own.
    let plain_once = |words: &[&'w str]| -> Vec<&'w str> {
        words
            .iter()
            .enumerate()
            .filter(|&(i, w)| {
                let between = i > 0
                    && words[i - 1] == "the"
                    && !opening(w)
                    && words.get(i + 1).is_some_and(|n| opening(n));
                !between || ZONE_WORDS.contains(w)
            })
            .map(|(_, w)| *w)
            .collect()
    };
    let once = plain_once(words);
    // "Entrance" before "doors" goes too: "the doors".
    let twice: Vec<&'w str> = once
        .iter()
        .enumerate()
        .filter(|&(i, w)| {
            !(*w == "entrance"
                && i > 0
                && once[i - 1] == "the"
                && once
                    .get(i + 1)
                    .is_some_and(|n| matches!(*n, "door" | "doors")))
        })
        .map(|(_, w)| *w)
        .collect();
    plain_once(&twice)
}

/// A relation word right after a mention with the next mention as its target: "facing",
/// "next to", "beside", "by", "near", "around", "in front of", "opposite", "across from", and
/// for pieces off the floor "on (top of, each)" and "(hung) above", "over".
fn relation_hint<'m>(
    phrase: &dyn Fn(&[&str]) -> bool,
    then_target: &dyn Fn(usize) -> Option<&'m Mention>,
) -> Option<Hint> {
    // `None`: facing, which is not a relation of the plan vocabulary.
    let relations: [(&[&str], Option<Relation>); 27] = [
        (&["facing"], None),
        // "Arrange the sofa so it faces the fireplace".
        (&["so", "it", "faces"], None),
        (&["so", "that", "it", "faces"], None),
        (&["so", "they", "face"], None),
        (&["faces"], None),
        (&["face"], None),
        (&["on", "each", "side", "of"], Some(Relation::SideOf)),
        (&["on", "either", "side", "of"], Some(Relation::SideOf)),
        // Off the floor: "a lamp on each nightstand", "the painting above the sofa".
        (&["on", "top", "of"], Some(Relation::On)),
        (&["on", "each"], Some(Relation::On)),
        (&["on", "every"], Some(Relation::On)),
        (&["on", "both"], Some(Relation::On)),
        (&["on"], Some(Relation::On)),
        (&["hung", "above"], Some(Relation::Above)),
        (&["hanging", "above"], Some(Relation::Above)),
        (&["mounted", "above"], Some(Relation::Above)),
        (&["above"], Some(Relation::Above)),
        (&["over"], Some(Relation::Above)),
        (&["next", "to"], Some(Relation::Near)),
        (&["beside"], Some(Relation::SideOf)),
        (&["flanking"], Some(Relation::SideOf)),
        (&["by"], Some(Relation::Near)),
        (&["near"], Some(Relation::Near)),
        (&["around"], Some(Relation::Around)),
        (&["in", "front", "of"], Some(Relation::InFrontOf)),
        (&["opposite"], Some(Relation::Opposite)),
        (&["across", "from"], Some(Relation::Opposite)),
    ];
    let (targets, relation) = relations.iter().find_map(|(p, r)| {
        phrase(p).then(|| then_target(p.len()).map(|t| (t.assets.clone(), *r)))?
    })?;
    Some(match relation {
        Some(r) => Hint::Relation(r, targets),
        None => Hint::Facing(targets),
    })
}

/// "A reading corner" or "a reading nook": the reading seats (armchairs and their kin) go in a
/// corner.
fn reading_corner(
    scene: &SceneSpec,
    knowledge: &Knowledge,
    tokens: &[String],
    mentions: &[Mention],
) -> Vec<PromptHint> {
    let Some(at) = tokens
        .windows(2)
        .position(|w| w[0] == "reading" && matches!(w[1].as_str(), "corner" | "nook"))
    else {
        return Vec::new();
    };
    let armchair = |i: &usize| {
        let kind = knowledge.kind_of(&scene.assets[*i]);
        kind.names.iter().any(|n| n == "armchair")
    };
    // The armchairs the sentence names after the words ("a reading corner: a wingback armchair
    // ..."), else every armchair.
    let end = tokens[at..]
        .iter()
        .position(|w| w == SENTENCE_END)
        .map_or(tokens.len(), |i| at + i);
    let named: Vec<usize> = mentions
        .iter()
        .filter(|m| !m.pronoun && m.start > at && m.end <= end)
        .flat_map(|m| m.assets.iter().copied())
        .filter(armchair)
        .collect();
    let seats: Vec<usize> = if named.is_empty() {
        (0..scene.assets.len()).filter(armchair).collect()
    } else {
        named
    };
    if seats.is_empty() {
        return Vec::new();
    }
    vec![PromptHint {
        subjects: seats,
        hint: Hint::Corner,
    }]
}

fn hint(m: &Mention, hint: Hint) -> PromptHint {
    PromptHint {
        subjects: m.assets.clone(),
        hint,
    }
}

fn skip_filler(tokens: &[String], mut i: usize) -> usize {
    // "Right next to it", "just behind": the word only stresses the place that follows.
    let stress = |i: usize| {
        matches!(tokens[i].as_str(), "right" | "just" | "directly")
            && tokens.get(i + 1).is_some_and(|n| {
                matches!(
                    n.as_str(),
                    "next" | "beside" | "by" | "behind" | "in" | "under" | "against" | "opposite"
                )
            })
    };
    while i < tokens.len() && (FILLER.contains(&tokens[i].as_str()) || stress(i)) {
        i += 1;
    }
    i
}

/// Singular of a plural word, when it looks like one.
fn singular(w: &str) -> String {
    for (plural, single) in [
        ("shelves", "shelf"),
        ("benches", "bench"),
        ("couches", "couch"),
    ] {
        if let Some(stem) = w.strip_suffix(plural) {
            return format!("{stem}{single}");
        }
    }
    if w.len() > 3 && w.ends_with('s') && !w.ends_with("ss") {
        w[..w.len() - 1].to_string()
    } else {
        w.to_string()
    }
}

/// Every longest run of up to four words that names assets: by their category, or by a
/// synonym of their kind.
fn find_mentions(scene: &SceneSpec, knowledge: &Knowledge, tokens: &[String]) -> Vec<Mention> {
    let kinds: Vec<_> = scene.assets.iter().map(|a| knowledge.kind_of(a)).collect();
    let named = |phrase: &str| -> Vec<usize> {
        let exact: Vec<usize> = (0..scene.assets.len())
            .filter(|&i| words(&scene.assets[i].category) == phrase)
            .collect();
        if !exact.is_empty() {
            return exact;
        }
        let mut by_kind: Vec<usize> = (0..scene.assets.len())
            .filter(|&i| kinds[i].names.iter().any(|n| n == phrase))
            .collect();
        // "Chairs" names office chairs too: a category is named by its head noun, its last word.
        if by_kind.is_empty() && !phrase.contains(' ') {
            by_kind = (0..scene.assets.len())
                .filter(|&i| words(&scene.assets[i].category).rsplit(' ').next() == Some(phrase))
                .collect();
        }
        // Last, a furniture word inside the category: "the TV" is the TV stand when the room
        // has no TV ("side" is no furniture word: "each long side" names no side table).
        if by_kind.is_empty() && !phrase.contains(' ') && knowledge.knows_exactly(phrase) {
            by_kind = (0..scene.assets.len())
                .filter(|&i| {
                    words(&scene.assets[i].category)
                        .split(' ')
                        .any(|w| w == phrase)
                })
                .collect();
        }
        // Then the assets' own names: "the seat" is `window-seat-0` when no category says
        // seat (its name without the number, or that name's last word).
        if by_kind.is_empty() {
            by_kind = (0..scene.assets.len())
                .filter(|&i| {
                    let name = words(&scene.assets[i].name);
                    let stem: Vec<&str> = name
                        .split(' ')
                        .filter(|w| !w.chars().all(|c| c.is_ascii_digit()))
                        .collect();
                    stem.join(" ") == phrase
                        || (!phrase.contains(' ') && stem.last() == Some(&phrase))
                })
                .collect();
        }
        // A kind may cover several fixtures ("tub" names the bath kind, which holds the toilet
        // and the shower too): those whose category holds the phrase are the ones meant.
        let in_category: Vec<usize> = by_kind
            .iter()
            .copied()
            .filter(|&i| words(&scene.assets[i].category).contains(phrase))
            .collect();
        if !in_category.is_empty() {
            return in_category;
        }
        // "Speaker" names the bookshelf speakers, not the floor lamp whose kind lists speakers
        // among its names: a category's own head noun comes before a kind's other names.
        let by_head: Vec<usize> = (0..scene.assets.len())
            .filter(|&i| words(&scene.assets[i].category).rsplit(' ').next() == Some(phrase))
            .collect();
        if by_head.is_empty() { by_kind } else { by_head }
    };
    let mut out: Vec<Mention> = Vec::new();
    let mut i = 0;
    // "The wine rack stands against the end wall", "should stand in the corner": a verb, not
    // the umbrella stand or the coat stand.
    let verb_use = |i: usize, out: &[Mention]| {
        matches!(
            tokens[i].as_str(),
            "stand" | "stands" | "sit" | "sits" | "rest" | "rests"
        ) && i > 0
            && (matches!(
                tokens[i - 1].as_str(),
                "should"
                    | "can"
                    | "will"
                    | "must"
                    | "may"
                    | "to"
                    | "would"
                    | "could"
                    | "shall"
                    | "it"
                    | "they"
                    | "which"
            ) || out.last().is_some_and(|m| m.end == i))
    };
    while i < tokens.len() {
        if verb_use(i, &out) {
            i += 1;
            continue;
        }
        let found = (1..=4.min(tokens.len() - i)).rev().find_map(|len| {
            let mut ws: Vec<String> = tokens[i..i + len].to_vec();
            let last = ws.len() - 1;
            let as_is = named(&ws.join(" "));
            if !as_is.is_empty() {
                return Some((len, as_is));
            }
            ws[last] = singular(&ws[last]);
            let single = named(&ws.join(" "));
            (!single.is_empty()).then_some((len, single))
        });
        // The word naming which one: the word before, or after "and" the word before the
        // mention just before ("the teacher's desk and chair": the teacher's chair).
        let before = i.checked_sub(1).map(|k| tokens[k].as_str()).and_then(|w| {
            if w != "and" {
                return Some(w);
            }
            // Its first word when it has several ("teacher desk"), else the word before it.
            out.last()
                .filter(|m: &&Mention| !m.pronoun && m.end + 1 == i)
                .and_then(|m| {
                    if m.end - m.start > 1 {
                        Some(m.start)
                    } else {
                        m.start.checked_sub(1)
                    }
                })
                .map(|k| tokens[k].as_str())
        });
        // "The student desks" are not the teacher's desk: when the words of the mention name
        // only some of the assets found (by name or category), those are the ones meant.
        let found = found.map(|(len, assets)| {
            let ws: Vec<String> = tokens[i..i + len].iter().map(|w| singular(w)).collect();
            let named_by_all = |a: usize| {
                let asset = &scene.assets[a];
                let text = format!("{} {}", words(&asset.name), words(&asset.category));
                ws.iter().all(|w| text.contains(w.as_str()))
            };
            let narrowed: Vec<usize> = assets
                .iter()
                .copied()
                .filter(|&a| named_by_all(a))
                .collect();
            if len > 1 && !narrowed.is_empty() && narrowed.len() < assets.len() {
                return (len, narrowed);
            }
            // "The window bench" when the category is just "bench": the word before names the
            // one meant, by its name.
            // ("Double desks": its description, "double student desk", says so.)
            let by_name: Vec<usize> = assets
                .iter()
                .copied()
                // "The teacher's demonstration wheel" names the teacher's wheel.
                .filter(|&a| before.is_some_and(|w| w.len() > 2 && says(&scene.assets[a], w)))
                .collect();
            if !by_name.is_empty() && by_name.len() < assets.len() {
                return (len, by_name);
            }
            // "The teacher's chair" when the chairs are `chair` and the teacher's an `office
            // chair`: the asset whose name holds the word and whose category ends in the noun.
            let noun = singular(&tokens[i + len - 1]);
            // "The patient chair" when it is the `dental chair` described "patient chair": its
            // description says so.
            let others: Vec<usize> = (0..scene.assets.len())
                .filter(|a| !assets.contains(a))
                .filter(|&a| {
                    let asset = &scene.assets[a];
                    before.is_some_and(|w| w.len() > 2 && says(asset, w))
                        && words(&asset.category).rsplit(' ').next() == Some(noun.as_str())
                })
                .collect();
            if others.is_empty() {
                (len, assets)
            } else {
                (len, others)
            }
        });
        match found {
            Some((len, assets)) => {
                out.push(Mention {
                    start: i,
                    end: i + len,
                    assets,
                    pronoun: false,
                });
                i += len;
            }
            // "The desk with the chair in front of it", "the sofa and the TV with the table
            // between them": a pronoun names what the sentence named last ("them": the last
            // mentions joined by "and").
            // Named below, once the assets are shared out.
            None if matches!(tokens[i].as_str(), "it" | "them") => {
                out.push(Mention {
                    start: i,
                    end: i + 1,
                    assets: Vec::new(),
                    pronoun: true,
                });
                i += 1;
            }
            None => i += 1,
        }
    }
    leave_to_narrower(&mut out);
    share_by_count(scene, tokens, &mut out);
    // "Its chair" names one seat, the one that serves what was just named; when the words name
    // a whole set an earlier mention already arranged ("the reading table with two chairs on
    // each long side, and the librarian's desk and its chair"), they name none of it: the
    // seating gives that desk its own chair.
    for k in 0..out.len() {
        let owned = out[k].start > 0 && tokens[out[k].start - 1] == "its";
        if owned
            && out[k].assets.len() > 1
            && out[..k]
                .iter()
                .any(|m| !m.pronoun && m.assets == out[k].assets)
        {
            out[k].assets.clear();
        }
    }
    out.retain(|m| m.pronoun || !m.assets.is_empty());
    // Pronouns name what their antecedents hold now that the assets are shared out; one that
    // names nothing is no mention.
    for k in 0..out.len() {
        if out[k].pronoun {
            out[k].assets = antecedent(scene, tokens, &out[..k], out[k].start).unwrap_or_default();
        }
    }
    out.retain(|m| !m.pronoun || !m.assets.is_empty());
    out
}

/// Whether `word` is a word of `asset`'s name or of its description (a possessive read as its
/// noun: "the teacher's demonstration wheel" says "teacher").
fn says(asset: &disco_core::scene::Asset, word: &str) -> bool {
    let described = asset.description.as_deref().map(words).unwrap_or_default();
    let name = words(&asset.name);
    name.split(' ')
        .chain(
            described
                .split(|c: char| !(c.is_alphanumeric() || c == '\''))
                .map(|w| w.strip_suffix("'s").unwrap_or(w)),
        )
        .any(|n| n == word)
}

/// "Two armchairs facing each other ... a wingback armchair by the window": mentions of the same
/// assets that each count theirs ("two", "a", "one") and together count no more than there are
/// share them out, in the prompt's order, each taking first the assets whose name or
/// description holds the mention's own words ("wingback").
fn share_by_count(scene: &SceneSpec, tokens: &[String], mentions: &mut [Mention]) {
    // The count before the noun, past up to two describing words ("a wingback armchair"); none
    // for a distributive mention ("a music stand in front of each chair" is one per chair).
    let count_of = |m: &Mention| -> Option<usize> {
        let after = &tokens[m.end..(m.end + 6).min(tokens.len())];
        if after
            .iter()
            .take_while(|w| *w != CLAUSE_END && *w != SENTENCE_END)
            .any(|w| matches!(w.as_str(), "each" | "every" | "per"))
        {
            return None;
        }
        tokens[m.start.saturating_sub(3)..m.start]
            .iter()
            .rev()
            .take_while(|w| *w != CLAUSE_END && *w != SENTENCE_END)
            .find_map(|w| match w.as_str() {
                // "Its chair": one, the one that goes with what was just named.
                "a" | "an" | "one" | "another" | "its" => Some(1),
                w => count_word(w),
            })
    };
    let mut done: Vec<Vec<usize>> = Vec::new();
    for k in 0..mentions.len() {
        let set = mentions[k].assets.clone();
        if mentions[k].pronoun || set.len() < 2 || done.contains(&set) {
            continue;
        }
        done.push(set.clone());
        let same: Vec<usize> = (k..mentions.len())
            .filter(|&j| !mentions[j].pronoun && mentions[j].assets == set)
            .collect();
        let counts: Option<Vec<usize>> = same.iter().map(|&j| count_of(&mentions[j])).collect();
        let Some(counts) = counts else { continue };
        if same.len() < 2 || counts.iter().sum::<usize>() > set.len() || counts.contains(&0) {
            continue;
        }
        let mut left = set.clone();
        for (&j, &n) in same.iter().zip(&counts) {
            // The words before the noun within the mention's phrase ("wingback" in "a wingback
            // armchair"): up to three words back, stopping at the count.
            let from = mentions[j].start.saturating_sub(3);
            let own: Vec<&str> = tokens[from..mentions[j].start]
                .iter()
                .rev()
                .take_while(|w| count_word(w).is_none() && !matches!(w.as_str(), "a" | "an"))
                .map(String::as_str)
                .filter(|w| w.len() > 3)
                .collect();
            let said = |a: usize| {
                let asset = &scene.assets[a];
                let text = format!(
                    "{} {}",
                    words(&asset.name),
                    asset.description.as_deref().map(words).unwrap_or_default()
                );
                own.iter().any(|w| text.contains(w))
            };
            let mut order = left.clone();
            order.sort_by_key(|&a| !said(a));
            let mut mine: Vec<usize> = order.into_iter().take(n).collect();
            mine.sort_unstable();
            left.retain(|a| !mine.contains(a));
            mentions[j].assets = mine;
        }
        // Assets no count took stay with every mention's neighbours: the last one takes them.
        if let Some(&last) = same.last() {
            mentions[last].assets.extend(left);
            mentions[last].assets.sort_unstable();
        }
    }
}

/// "Two armchairs facing each other ... a wingback armchair by the window": an asset a narrower
/// mention names (one naming a strict subset of a mention's assets) is that mention's, not the
/// wider one's, as long as the wider one keeps some.
fn leave_to_narrower(mentions: &mut [Mention]) {
    let sets: Vec<Vec<usize>> = mentions.iter().map(|m| m.assets.clone()).collect();
    for (k, m) in mentions.iter_mut().enumerate() {
        if m.pronoun || m.assets.len() < 2 {
            continue;
        }
        let narrower: Vec<usize> = sets
            .iter()
            .enumerate()
            .filter(|(j, b)| {
                *j != k && b.len() < sets[k].len() && b.iter().all(|a| sets[k].contains(a))
            })
            .flat_map(|(_, b)| b.iter().copied())
            .collect();
        if m.assets.iter().any(|a| !narrower.contains(a)) {
            m.assets.retain(|a| !narrower.contains(a));
        }
    }
}

/// What the pronoun at `at` ("it" or "them") names, in its sentence. The mention just before
/// it is the phrase's subject ("the chair in front of it"), so the pronoun names what came
/// before that: for "it" the one mention, for "them" that mention's assets when it names
/// several, else it and the mention before ("the sofa facing the TV, the table between them").
/// A pronoun with nothing before its subject names the subject's predecessor in the sentence
/// only; `None` when there is none.
fn antecedent(
    scene: &SceneSpec,
    tokens: &[String],
    mentions: &[Mention],
    at: usize,
) -> Option<Vec<usize>> {
    let in_sentence = |m: &Mention| !tokens[m.end..at].iter().any(|w| w == SENTENCE_END);
    // A rug is walked on, not referred back to ("the table on a rug ... across it"), unless
    // the phrase's own subject lies flat too ("the instructor's mat ..., eight mats in two rows
    // facing it").
    let flat = |m: &Mention| m.assets.iter().all(|&a| scene.assets[a].is_flat());
    let said: Vec<&Mention> = mentions
        .iter()
        .filter(|m| !m.pronoun && in_sentence(m))
        .collect();
    let flat_subject = said.last().is_some_and(|m| flat(m));
    let candidates: Vec<&Mention> = said
        .into_iter()
        .filter(|m| flat_subject || !flat(m))
        .collect();
    // Drop the subject: the last mention before the pronoun.
    let before = candidates.split_last()?.1;
    // "It" names one thing, the sentence's topic: "a bed with a lamp on each nightstand and a
    // painting above it", "the TV on the wall facing the sofa, a console under it"; after
    // "each (with)", the things just named: "six easels, each with a stool behind it".
    let subject = candidates.last()?;
    let distributive = tokens[subject.start.saturating_sub(3)..subject.start]
        .iter()
        .any(|w| matches!(w.as_str(), "each" | "every"));
    let same_clause = |m: &&&Mention| {
        !tokens[m.end..subject.start]
            .iter()
            .any(|w| w == CLAUSE_END || w == SENTENCE_END)
    };
    let last = if tokens[at] == "it" && !distributive {
        // The nearest single thing in the subject's clause ("a dresser with a mirror above
        // it"), else the sentence's first ("the TV on the wall ..., a console under it").
        before
            .iter()
            .rev()
            .filter(same_clause)
            .find(|m| m.assets.len() == 1)
            .or_else(|| before.iter().find(|m| m.assets.len() == 1))
            .or(before.last())?
    } else {
        before.last()?
    };
    let mut assets = last.assets.clone();
    if tokens[at] == "them"
        && assets.len() < 2
        && let Some(previous) = before.len().checked_sub(2).map(|k| before[k])
    {
        assets.extend(previous.assets.iter().copied());
    }
    Some(assets)
}

#[cfg(test)]
mod tests {
    use super::*;
    use disco_core::scene::{Asset, Room};

    fn scene(prompt: &str, cats: &[&str]) -> SceneSpec {
        SceneSpec {
            id: "t".into(),
            prompt: prompt.into(),
            room_type: "room".into(),
            room: Room::rect(500.0, 400.0),
            assets: cats
                .iter()
                .enumerate()
                .map(|(i, c)| Asset {
                    name: format!("{c}-{i}"),
                    category: c.to_string(),
                    size: [50.0, 50.0, 50.0],
                    mesh: None,
                    description: None,
                    support: None,
                })
                .collect(),
        }
    }

    fn read(prompt: &str, cats: &[&str]) -> Vec<PromptHint> {
        read_hints(&scene(prompt, cats), &Knowledge::builtin())
    }

    fn unread(prompt: &str, cats: &[&str]) -> Vec<String> {
        unread_phrases(&scene(prompt, cats), &Knowledge::builtin())
    }

    #[test]
    fn a_place_said_first_holds_the_sentence() {
        let hints = read(
            "In the left wing two sofas face each other across a coffee table; a desk by the door.",
            &["sofa", "sofa", "coffee table", "desk"],
        );
        let wing = hints
            .iter()
            .find(|h| matches!(&h.hint, Hint::Place(p) if p.zone.as_deref() == Some("wing-left")))
            .expect("the left wing is read");
        assert_eq!(wing.subjects, vec![0, 1, 2]);
        // A description of the room is no place: "a bedroom with one angled wall: a bed".
        assert!(
            !read(
                "A bedroom with one angled wall: a bed and a desk.",
                &["bed", "desk"]
            )
            .iter()
            .any(|h| matches!(h.hint, Hint::Place(_)))
        );
    }

    #[test]
    fn counted_mentions_share_their_assets() {
        // Two of the three armchairs face each other at the table; the wingback one (by its
        // description) goes to the reading corner with the lamp beside it.
        let mut s = scene(
            "two armchairs facing each other across the coffee table. A reading corner: a wingback armchair with a floor lamp beside it.",
            &[
                "armchair",
                "armchair",
                "armchair",
                "coffee table",
                "floor lamp",
            ],
        );
        s.assets[2].description = Some("wingback reading chair".into());
        let hints = read_hints(&s, &Knowledge::builtin());
        assert!(hints.contains(&PromptHint {
            subjects: vec![0, 1],
            hint: Hint::Relation(Relation::Around, vec![3]),
        }));
        assert!(hints.contains(&PromptHint {
            subjects: vec![4],
            hint: Hint::Relation(Relation::SideOf, vec![2]),
        }));
        assert!(hints.contains(&PromptHint {
            subjects: vec![2],
            hint: Hint::Corner,
        }));
    }

    fn formation_of(hints: &[PromptHint]) -> Option<(Vec<usize>, FormationHint)> {
        hints.iter().find_map(|h| match &h.hint {
            Hint::Formation(f) => Some((h.subjects.clone(), f.clone())),
            _ => None,
        })
    }

    #[test]
    fn two_rows_facing_each_other_across_a_table_sit_down_its_long_sides() {
        let mut cats = vec!["chair"; 8];
        cats.push("coffee table");
        let hints = read(
            "Two rows of four waiting chairs facing each other across the coffee table.",
            &cats,
        );
        let (members, f) = formation_of(&hints).expect("the rows are read");
        assert_eq!(members, (0..8).collect::<Vec<_>>());
        assert_eq!(
            (f.shape, f.count, f.focus),
            (FormationShape::PerSide, Some(4), vec![8])
        );
    }

    #[test]
    fn the_teachers_desk_and_chair_name_the_teachers_chair() {
        let mut s = scene(
            "Four desks, each with its chair; the teacher's desk and chair near the board.",
            &[
                "desk",
                "desk",
                "chair",
                "chair",
                "desk",
                "office chair",
                "board",
            ],
        );
        s.assets[4].name = "teacher-desk-0".into();
        s.assets[5].name = "teacher-chair-0".into();
        let hints = read_hints(&s, &Knowledge::builtin());
        let near_board: Vec<&PromptHint> = hints
            .iter()
            .filter(|h| matches!(&h.hint, Hint::Relation(Relation::Near, t) if t == &vec![6]))
            .collect();
        let named: Vec<usize> = near_board.iter().flat_map(|h| h.subjects.clone()).collect();
        assert!(named.contains(&5), "{hints:?}");
        assert!(!named.contains(&2) && !named.contains(&3), "{hints:?}");
    }

    #[test]
    fn mats_in_rows_facing_it_face_the_mat_just_named() {
        let mut s = scene(
            "Lay the instructor's mat by the far wall, and eight mats in two rows of four facing it.",
            &["yoga mat"; 9],
        );
        s.assets[0].name = "instructor-mat-0".into();
        for a in &mut s.assets {
            a.size = [65.0, 185.0, 1.0];
        }
        let hints = read_hints(&s, &Knowledge::builtin());
        let (_, f) = formation_of(&hints).expect("the rows are read");
        assert_eq!((f.shape, f.count), (FormationShape::Rows, Some(2)));
        assert_eq!(f.focus, vec![0], "{hints:?}");
    }

    #[test]
    fn its_chair_is_the_pieces_own_not_a_set_arranged_before() {
        // Assets: the reading table, four chairs, the librarian's desk, an office chair.
        let cats = [
            "reading table",
            "chair",
            "chair",
            "chair",
            "chair",
            "desk",
            "office chair",
        ];
        let hints = read(
            "The reading table with two chairs on each long side, and the desk and its chair by the entrance.",
            &cats,
        );
        let by_door = hints
            .iter()
            .find(|h| matches!(&h.hint, Hint::Place(p) if p.by_entrance))
            .expect("the entrance is read");
        assert!(by_door.subjects.contains(&5), "{hints:?}");
        assert!(
            !(1..=4).any(|c| by_door.subjects.contains(&c)),
            "the table's chairs stay at the table: {hints:?}"
        );
        // Under a window, the desk's: its chair sits at it, off the wall.
        let hints = read(
            "The writing desk and its chair under the window.",
            &["desk", "chair"],
        );
        let under = hints
            .iter()
            .find(|h| matches!(&h.hint, Hint::Place(p) if p.under_window))
            .expect("the window is read");
        assert_eq!(under.subjects, vec![0], "{hints:?}");
    }

    #[test]
    fn rows_facing_a_bare_wall_name_the_wall() {
        // No whiteboard among the assets: the rows face the wall the sentence names.
        let hints = read(
            "Eight desks in four rows of two, all facing the whiteboard on the left wall.",
            &[
                "desk", "desk", "desk", "desk", "desk", "desk", "desk", "desk",
            ],
        );
        let rows = hints
            .iter()
            .find_map(|h| match &h.hint {
                Hint::Formation(f) if f.shape == FormationShape::Rows => Some(f),
                _ => None,
            })
            .expect("the rows are read");
        assert_eq!((rows.count, rows.wall), (Some(4), Some(WallRole::Left)));
        assert!(rows.focus.is_empty());
    }

    #[test]
    fn a_companion_with_its_keeps_out_of_the_next_clause_s_place() {
        let hints = read(
            "Desk under the window with its chair, wardrobe against the left wall.",
            &["desk", "office chair", "wardrobe"],
        );
        let left = hints
            .iter()
            .find(|h| matches!(&h.hint, Hint::Place(p) if p.wall == Some(WallRole::Left)))
            .expect("the wardrobe's wall is read");
        assert_eq!(left.subjects, vec![2]);
    }

    #[test]
    fn a_mention_for_each_is_not_counted() {
        // "A stand in front of each chair, plus one stand at the podium": all the stands stay
        // the first mention's (one per chair; the planner sends the extra to the podium).
        let hints = read(
            "three chairs facing the podium with a music stand in front of each chair, plus one stand at the podium",
            &[
                "chair",
                "chair",
                "chair",
                "podium",
                "music stand",
                "music stand",
                "music stand",
                "music stand",
            ],
        );
        let per = hints
            .iter()
            .find(|h| matches!(&h.hint, Hint::Formation(f) if f.shape == FormationShape::OnePerMember))
            .expect("one per member is read");
        assert_eq!(per.subjects, vec![4, 5, 6, 7]);
    }

    #[test]
    fn it_names_the_clause_s_thing_else_the_sentence_s_topic() {
        let cats = ["tv", "sofa", "media console", "dresser", "mirror"];
        let hints = read(
            "the tv on the wall facing the sofa, a media console under it. a dresser with a mirror above it.",
            &cats,
        );
        assert!(hints.contains(&PromptHint {
            subjects: vec![2],
            hint: Hint::Under(vec![0]),
        }));
        assert!(hints.contains(&PromptHint {
            subjects: vec![4],
            hint: Hint::Relation(Relation::Above, vec![3]),
        }));
    }

    #[test]
    fn behind_between_and_ends() {
        let hints = read(
            "the counter with two chairs behind it, the table between the sofas, a lamp at the end of the bench",
            &[
                "counter", "chair", "chair", "table", "sofa", "sofa", "lamp", "bench",
            ],
        );
        assert!(hints.contains(&PromptHint {
            subjects: vec![1, 2],
            hint: Hint::Behind(vec![0]),
        }));
        assert!(hints.contains(&PromptHint {
            subjects: vec![3],
            hint: Hint::Between(vec![4, 5]),
        }));
        assert!(hints.contains(&PromptHint {
            subjects: vec![6],
            hint: Hint::Relation(Relation::SideOf, vec![7]),
        }));
    }

    #[test]
    fn placement_words_no_hint_came_of_are_quoted() {
        // "between" is no relation the reader knows: the clause is quoted, the rest is not.
        assert_eq!(
            unread(
                "The bed between the two windows, a nightstand on each side, the sofa facing the tv.",
                &["bed", "nightstand", "sofa", "tv"]
            ),
            vec!["bed between the two windows".to_string()]
        );
        // A relation the reader knows leaves nothing behind, its target included.
        assert!(unread("the sofa facing the tv", &["sofa", "tv"]).is_empty());
        // A mention with no placement words asks for nothing.
        assert!(unread("a sofa and a rug and a tv", &["sofa", "rug", "tv"]).is_empty());
        // A pronoun names what its phrase's subject was about.
        assert!(
            unread(
                "the desk under the window with the office chair in front of it",
                &["desk", "office chair"]
            )
            .is_empty()
        );
        let hints = read(
            "the desk under the window with the office chair in front of it",
            &["desk", "office chair"],
        );
        assert!(hints.contains(&PromptHint {
            subjects: vec![1],
            hint: Hint::Relation(Relation::InFrontOf, vec![0]),
        }));
        // Seats of a ring facing its centre say nothing more than the ring does.
        assert!(
            unread(
                "ten chairs in a closed circle around the rug, every chair facing the centre",
                &["chair", "rug"]
            )
            .is_empty()
        );
        assert_eq!(
            unread("the chair facing the centre", &["chair"]),
            vec!["chair facing the centre".to_string()]
        );
        // The words run to the next mention: "the desk diagonal to the bookshelf".
        assert_eq!(
            unread("the desk diagonal to the bookshelf", &["desk", "bookshelf"]),
            vec!["desk diagonal to the bookshelf".to_string()]
        );
    }

    #[test]
    fn spots() {
        let h = read(
            "a dining room with a round table in the center and a plant in a corner, shelves along the walls",
            &["round table", "potted plant", "bookshelf"],
        );
        assert_eq!(
            h,
            vec![
                PromptHint {
                    subjects: vec![0],
                    hint: Hint::Centre
                },
                PromptHint {
                    subjects: vec![1],
                    hint: Hint::Corner
                },
                PromptHint {
                    subjects: vec![2],
                    hint: Hint::AlongWall
                },
            ]
        );
    }

    #[test]
    fn a_freed_piece_is_the_one_named_not_its_whole_kind() {
        // "tub" names the bath kind, which also holds the toilet and the shower: only the
        // bathtub is meant.
        let h = read(
            "a spa bathroom with a freestanding tub in the middle",
            &["bathtub", "toilet", "shower"],
        );
        assert_eq!(
            h,
            vec![PromptHint {
                subjects: vec![0],
                hint: Hint::Centre
            }]
        );
        let h = read("a loft where the bed stands free", &["bed", "wardrobe"]);
        assert_eq!(h[0].subjects, vec![0]);
        assert_eq!(h[0].hint, Hint::Centre);
    }

    #[test]
    fn arranged_around_is_around() {
        let h = read(
            "a lounge with four armchairs arranged around the fire pit",
            &["fire pit", "armchair"],
        );
        assert_eq!(h[0].subjects, vec![1]);
        assert_eq!(h[0].hint, Hint::Relation(Relation::Around, vec![0]));
        let h = read("the desk tucked into the corner", &["desk"]);
        assert_eq!(h[0].hint, Hint::Corner);
    }

    #[test]
    fn a_reading_corner_puts_the_armchairs_in_a_corner() {
        let h = read(
            "a cozy bedroom with a reading corner",
            &["bed", "armchair", "floor lamp"],
        );
        assert_eq!(
            h,
            vec![PromptHint {
                subjects: vec![1],
                hint: Hint::Corner
            }]
        );
        assert!(read("a cozy bedroom", &["bed", "armchair"]).is_empty());
    }

    #[test]
    fn relations_by_category_or_synonym_and_plural() {
        let h = read(
            "a living room with a sofa facing the TV and a lamp next to the couch",
            &["sofa", "tv stand", "floor lamp"],
        );
        assert_eq!(h[0].subjects, vec![0]);
        assert_eq!(h[0].hint, Hint::Facing(vec![1]));
        assert_eq!(h[1].hint, Hint::Relation(Relation::Near, vec![0]));
        let h = read(
            "a modern kitchen with a central island surrounded by bar stools",
            &["kitchen island", "bar stool", "bar stool"],
        );
        assert_eq!(h[0].hint, Hint::Centre);
        assert_eq!(
            h[1],
            PromptHint {
                subjects: vec![1, 2],
                hint: Hint::Relation(Relation::Around, vec![0])
            }
        );
        let h = read(
            "four chairs around the table",
            &["dining table", "chair", "chair"],
        );
        assert_eq!(h[0].subjects, vec![1, 2]);
        assert_eq!(h[0].hint, Hint::Relation(Relation::Around, vec![0]));
    }

    #[test]
    fn a_piece_by_the_window_is_a_window_hint() {
        for prompt in [
            "a home office with a desk by the window",
            "a desk near the windows and a bookshelf",
            "a bedroom, the desk under the window",
            "an armchair next to the window",
        ] {
            let h = read(prompt, &["desk", "armchair", "bookshelf"]);
            let by_window: Vec<&PromptHint> =
                h.iter().filter(|h| h.hint == Hint::ByWindow).collect();
            assert_eq!(by_window.len(), 1, "{prompt}: {h:?}");
            // "Under the window" also says where: under it, not merely by it.
            let under = h
                .iter()
                .any(|h| matches!(&h.hint, Hint::Place(p) if p.under_window));
            assert_eq!(under, prompt.contains("under"), "{prompt}: {h:?}");
        }
        // "Facing the window" says which way a piece looks, not where it stands.
        assert!(read("a desk facing the window", &["desk"]).is_empty());
    }

    #[test]
    fn no_hints_in_a_bare_label_or_about_absent_things() {
        assert!(read("a kitchen", &["refrigerator"]).is_empty());
        assert!(read("a bed facing the window", &["bed"]).is_empty());
    }

    #[test]
    fn places_in_the_room_are_read_by_the_rooms_parts() {
        let place = |words: &str| place_in_room(&words.split(' ').collect::<Vec<_>>());
        let p = place("headboard against the wall opposite the door").unwrap();
        assert_eq!(p.wall, Some(WallRole::OppositeDoor));
        assert_eq!(
            place("in the alcove under its window")
                .unwrap()
                .zone
                .as_deref(),
            Some("recess")
        );
        assert!(
            place("in the alcove under its window")
                .unwrap()
                .under_window
        );
        assert_eq!(
            place("in the short arm of the l").unwrap().zone.as_deref(),
            Some("wing")
        );
        // "Side" of "each long side" is no zone word: the wide part is the main area.
        let p = place("in the wide part with four chairs on each long side").unwrap();
        assert_eq!(p.zone.as_deref(), Some("main"));
        assert_eq!(
            place("on the long windowless wall").unwrap().wall,
            Some(WallRole::LongestSolid)
        );
        assert_eq!(
            place("along the slanted wall").unwrap().wall,
            Some(WallRole::Slanted)
        );
        assert!(
            place("in the corner farthest from the door")
                .unwrap()
                .far_corner
        );
        assert!(place("by the entrance").unwrap().by_entrance);
        assert!(place("next to the sofa").is_none());
    }

    #[test]
    fn a_place_ends_with_its_clause_and_covers_the_party_before_it() {
        let h = read(
            "two bookshelves along the slanted wall, a storage cabinet by the entrance",
            &["bookshelf", "bookshelf", "storage cabinet"],
        );
        let places: Vec<(&Vec<usize>, &Place)> = h
            .iter()
            .filter_map(|h| match &h.hint {
                Hint::Place(p) => Some((&h.subjects, p)),
                _ => None,
            })
            .collect();
        assert_eq!(places.len(), 2, "{h:?}");
        assert_eq!(places[0].0, &vec![0, 1]);
        assert_eq!(places[0].1.wall, Some(WallRole::Slanted));
        assert!(!places[0].1.by_entrance);
        assert_eq!(places[1].0, &vec![2]);
        assert!(places[1].1.by_entrance);
        let h = read(
            "a reading armchair with a floor lamp in the short arm of the L",
            &["armchair", "floor lamp"],
        );
        let party = h.iter().find(|h| matches!(h.hint, Hint::Place(_))).unwrap();
        assert_eq!(party.subjects, vec![0, 1]);
    }

    #[test]
    fn formations_with_counts_and_their_focus() {
        let formation = |prompt: &str, cats: &[&str]| -> Vec<(Vec<usize>, FormationHint)> {
            read(prompt, cats)
                .into_iter()
                .filter_map(|h| match h.hint {
                    Hint::Formation(f) => Some((h.subjects, f)),
                    _ => None,
                })
                .collect()
        };
        let f = formation(
            "six chairs in a semicircle facing the piano",
            &["piano", "chair", "chair"],
        );
        assert_eq!(f[0].0, vec![1, 2]);
        assert_eq!(
            (f[0].1.shape, f[0].1.focus.clone()),
            (FormationShape::Arc, vec![0])
        );
        let f = formation(
            "two rows of four student desks, each desk with its chair, students facing the whiteboard",
            &["student desk", "teacher desk", "chair", "whiteboard"],
        );
        assert_eq!(
            f[0].0,
            vec![0],
            "the student desks only, not the teacher's: {f:?}"
        );
        assert_eq!(f[0].1.shape, FormationShape::Rows);
        assert_eq!((f[0].1.count, f[0].1.focus.clone()), (Some(2), vec![3]));
        let f = formation("two pods of four desks", &["desk"]);
        assert_eq!(
            (f[0].1.shape, f[0].1.count),
            (FormationShape::Pods, Some(2))
        );
        let f = formation(
            "the conference table with four chairs on each long side",
            &["conference table", "office chair"],
        );
        assert_eq!(f[0].1.shape, FormationShape::PerSide);
        assert_eq!((f[0].1.count, f[0].1.focus.clone()), (Some(4), vec![0]));
        let f = formation(
            "chairs in an arc, a music stand in front of each chair",
            &["chair", "music stand"],
        );
        let stands = f
            .iter()
            .find(|(_, f)| f.shape == FormationShape::OnePerMember)
            .unwrap();
        assert_eq!((stands.0.clone(), stands.1.of.clone()), (vec![1], vec![0]));
        // A closed circle about a rug; the rows counted after the noun; a stool behind each.
        let f = formation(
            "ten chairs in a closed circle around the round rug",
            &["chair", "rug"],
        );
        assert_eq!(
            (f[0].1.shape, f[0].1.focus.clone()),
            (FormationShape::Ring, vec![1])
        );
        let f = formation("chairs in a circle, facing in", &["chair"]);
        assert_eq!(f[0].1.shape, FormationShape::Ring);
        assert!(formation("chairs in a semicircle", &["chair"])[0].1.shape == FormationShape::Arc);
        let f = formation(
            "eight desks in four rows of two, all facing the whiteboard",
            &["desk", "whiteboard"],
        );
        assert_eq!(
            (f[0].1.shape, f[0].1.count, f[0].1.focus.clone()),
            (FormationShape::Rows, Some(4), vec![1])
        );
        let f = formation(
            "the platform by the wall, six easels in an arc facing it, each with a stool behind it",
            &["easel", "stool", "platform"],
        );
        let behind = f
            .iter()
            .find(|(_, f)| f.shape == FormationShape::BehindEach)
            .unwrap();
        assert_eq!((behind.0.clone(), behind.1.of.clone()), (vec![1], vec![0]));
        assert!(
            formation("a stool behind the easel", &["easel", "stool"]).is_empty(),
            "one behind one is no formation"
        );
        // Rows back to back with nothing to face stand free, their fronts out.
        let f = formation("chairs in two rows back to back", &["chair"]);
        assert_eq!(
            (f[0].1.shape, f[0].1.count),
            (FormationShape::Aisles, Some(2))
        );
    }

    #[test]
    fn u_and_l_formations_are_read() {
        let letter = |prompt: &str, cats: &[&str]| -> Vec<(Vec<usize>, FormationHint)> {
            read_hints(&scene(prompt, cats), &Knowledge::builtin())
                .into_iter()
                .filter_map(|h| match h.hint {
                    Hint::Formation(f)
                        if matches!(f.shape, FormationShape::UTables | FormationShape::LDesks) =>
                    {
                        Some((h.subjects, f))
                    }
                    _ => None,
                })
                .collect()
        };
        let cats = ["meeting table", "office chair", "presentation screen"];
        let f = letter(
            "Six tables in a U whose open end faces the presentation screen on the left wall, \
             with chairs only around the outside of the U, two per table.",
            &cats,
        );
        assert_eq!(f.len(), 1, "{f:?}");
        assert_eq!(f[0].0, vec![0]);
        assert_eq!(
            (f[0].1.shape, f[0].1.count, f[0].1.focus.clone()),
            (FormationShape::UTables, Some(2), vec![2])
        );
        let f = letter("a U-shaped table layout facing the screen", &cats);
        assert_eq!(
            (f[0].1.shape, f[0].1.focus.clone()),
            (FormationShape::UTables, vec![2])
        );
        let f = letter(
            "A training room with a horseshoe of tables and chairs around the outside",
            &["table", "chair", "whiteboard"],
        );
        // The chairs named after the tables are not a U of their own.
        assert_eq!(f.len(), 1, "{f:?}");
        assert_eq!(f[0].0, vec![0]);
        let f = letter("a horseshoe of tables", &cats);
        assert_eq!(
            (f[0].1.shape, f[0].1.count),
            (FormationShape::UTables, None)
        );
        assert_eq!(
            letter("tables arranged in a U", &cats)[0].1.shape,
            FormationShape::UTables
        );
        // No letter, no U: chairs "around the outside" alone are not a formation of this kind.
        assert!(letter("six tables with chairs around them", &cats).is_empty());
        let cats = ["desk", "office chair"];
        let f = letter("L-shaped desk in the corner farthest from the door", &cats);
        assert_eq!(
            (f[0].0.clone(), f[0].1.shape),
            (vec![0], FormationShape::LDesks)
        );
        let f = letter("two desks in an L, the chair in the crook", &cats);
        assert_eq!(f[0].1.shape, FormationShape::LDesks);
        assert!(letter("a desk under the window", &cats).is_empty());
    }

    /// `scene` with a description on some of its assets, by index.
    fn described(cats: &[&str], said: &[(usize, &str)]) -> SceneSpec {
        let mut s = scene("a room", cats);
        for (i, text) in said {
            s.assets[*i].description = Some((*text).into());
        }
        s
    }

    #[test]
    fn a_description_asks_for_the_run_of_alike_pieces_it_opens() {
        let cats = [
            "hemodialysis machine",
            "hemodialysis machine",
            "hemodialysis machine",
            "dialysis chair",
            "dialysis chair",
            "dialysis chair",
        ];
        let s = described(&cats, &[(0, "beside a dialysis chair")]);
        let hints = described_hints(&s, &Knowledge::builtin());
        assert!(
            hints.iter().any(|h| h.subjects == [0, 1, 2]
                && matches!(&h.hint, Hint::Relation(_, t) if t == &vec![3, 4, 5])),
            "{hints:?}"
        );
        // A description that asks nothing of where its piece goes gives nothing.
        let s = described(&cats, &[(0, "wipe-clean and quiet")]);
        assert!(described_hints(&s, &Knowledge::builtin()).is_empty());
    }

    #[test]
    fn a_description_is_read_from_the_word_that_opens_a_place_and_repeats_are_one_run() {
        let cats = [
            "pedicure stool",
            "pedicure stool",
            "pedicure chair",
            "pedicure chair",
        ];
        let said = "technician sits at the footbath in front of a pedicure chair";
        let s = described(&cats, &[(0, said), (1, said)]);
        let hints = described_hints(&s, &Knowledge::builtin());
        assert_eq!(hints.len(), 1, "{hints:?}");
        assert_eq!(hints[0].subjects, vec![0, 1]);
        assert!(
            matches!(&hints[0].hint, Hint::Relation(Relation::InFrontOf, t) if t == &vec![2, 3]),
            "{hints:?}"
        );
        // A second description that asks something else opens a run of its own.
        let s = described(&cats, &[(0, said), (1, "in the corner")]);
        let hints = described_hints(&s, &Knowledge::builtin());
        assert!(hints.iter().any(|h| h.subjects == [0]), "{hints:?}");
        assert!(hints.iter().any(|h| h.subjects == [1]), "{hints:?}");
    }
    #[test]
    fn a_companion_takes_neither_its_piece_s_window_nor_the_next_clause_s_wall() {
        // "Its chair under the window": the window is the desk's, the chair sits at it.
        let cats = ["table", "chair", "chair", "desk", "chair", "luggage rack"];
        let hints = read(
            "Put the small round table and its two chairs in the bay, the writing desk and its chair under the window on the wall opposite the bay, and the luggage rack by the entrance.",
            &cats,
        );
        assert!(
            !hints.iter().any(|h| h.subjects.contains(&4)
                && matches!(&h.hint, Hint::ByWindow | Hint::AlongWall | Hint::Place(_))),
            "{hints:?}"
        );
        assert!(
            hints
                .iter()
                .any(|h| h.subjects == vec![3]
                    && matches!(&h.hint, Hint::Place(p) if p.under_window))
        );
        // "Each with a chair, the wardrobe on the right": the wall is the wardrobe's alone.
        let hints = read(
            "Put the two desks side by side in the nook under its window, each with a chair, the wardrobe on the right as you come in.",
            &["desk", "desk", "chair", "chair", "wardrobe"],
        );
        let right = hints
            .iter()
            .find(|h| matches!(&h.hint, Hint::Place(p) if p.wall == Some(WallRole::RightFromDoor)))
            .expect("the wardrobe's wall is read");
        assert_eq!(right.subjects, vec![4], "{hints:?}");
    }

    #[test]
    fn a_place_phrase_goes_on_past_a_comma() {
        let hints = read(
            "Lay the instructor's mat at the front, by the wall opposite the entrance, and eight mats in two rows of four facing it.",
            &[
                "instructor mat",
                "mat",
                "mat",
                "mat",
                "mat",
                "mat",
                "mat",
                "mat",
                "mat",
            ],
        );
        let front = hints
            .iter()
            .find(|h| matches!(&h.hint, Hint::Place(p) if p.wall == Some(WallRole::OppositeDoor)))
            .expect("the wall opposite the entrance is read");
        assert_eq!(front.subjects, vec![0], "{hints:?}");
        // A new piece after the comma is a clause of its own.
        let hints = read(
            "The desk by the window, the wardrobe against the left wall.",
            &["desk", "wardrobe"],
        );
        assert!(
            !hints.iter().any(|h| h.subjects.contains(&0)
                && matches!(&h.hint, Hint::Place(p) if p.wall.is_some())),
            "{hints:?}"
        );
    }
    #[test]
    fn rows_are_read_as_columns_of_a_count_and_one_row_at_a_time() {
        let rows = |hints: &[PromptHint]| -> Vec<(Vec<usize>, Option<usize>, Vec<usize>)> {
            hints
                .iter()
                .filter_map(|h| match &h.hint {
                    Hint::Formation(f) if f.shape == FormationShape::Rows => {
                        Some((h.subjects.clone(), f.count, f.focus.clone()))
                    }
                    _ => None,
                })
                .collect()
        };
        // Two columns of four are four rows; the focus said far on, pointed back to.
        let mut cats = vec!["altar"];
        cats.extend(["pew"; 8]);
        let hints = read(
            "Set out the eight pews in two columns of four, one on each side of a centre aisle that runs straight from the main door up to the altar, all of them facing the altar.",
            &cats,
        );
        assert_eq!(rows(&hints), vec![((1..=8).collect(), Some(4), vec![0])]);
        // A front row and a back row are one formation of two rows.
        let mut cats = vec!["projection screen"];
        cats.extend(["recliner"; 7]);
        let hints = read(
            "Three recliners in a front row facing the screen, and the other four recliners in a back row behind them, also facing the screen.",
            &cats,
        );
        assert_eq!(rows(&hints), vec![((1..=7).collect(), Some(2), vec![0])]);
    }

    #[test]
    fn a_wall_s_middle_and_an_opening_s_own_word_are_read() {
        let hints = read(
            "Put the sideboard against the wall opposite the bay window, centred on it. The bench by the main entrance.",
            &["sideboard", "bench"],
        );
        assert!(
            hints
                .iter()
                .any(|h| h.subjects == vec![0] && h.hint == Hint::CentredOnWall)
        );
        assert!(
            hints.iter().any(
                |h| h.subjects == vec![1] && matches!(&h.hint, Hint::Place(p) if p.by_entrance)
            )
        );
        // The middle of a wall is no middle of the room; an opening named is before "back".
        let hints = read(
            "The easel goes in the middle of the back wall. The stations on the back wall, the long wall opposite the shop window.",
            &["easel", "station"],
        );
        assert!(
            hints
                .iter()
                .any(|h| h.subjects == vec![0] && h.hint == Hint::CentredOnWall)
        );
        assert!(!hints.iter().any(|h| h.hint == Hint::Centre), "{hints:?}");
        assert!(hints.iter().any(|h| h.subjects == vec![1]
            && matches!(&h.hint, Hint::Place(p) if p.wall == Some(WallRole::OppositeWindow))));
    }

    #[test]
    fn a_described_piece_is_named_by_a_word_of_its_description() {
        let mut s = scene(
            "The teacher's wheel goes against the back wall and the six student wheels in a semicircle facing it.",
            &["pottery wheel"; 7],
        );
        s.assets[0].description = Some("the teacher's demonstration wheel".into());
        let hints = read_hints(&s, &Knowledge::builtin());
        let arc = hints
            .iter()
            .find(|h| matches!(&h.hint, Hint::Formation(f) if f.shape == FormationShape::Arc))
            .expect("the semicircle is read");
        assert_eq!(arc.subjects, (1..=6).collect::<Vec<_>>());
        assert!(matches!(&arc.hint, Hint::Formation(f) if f.focus == vec![0]));
    }
    #[test]
    fn a_place_before_its_pieces_is_read_with_its_side_and_its_list() {
        // "In the snug to the left of the bar": the left wing; the bar tells the place.
        let hints = read(
            "In the snug to the left of the bar, put the fireplace against the end wall and the armchair facing it.",
            &["bar counter", "fireplace", "armchair"],
        );
        let wing = hints
            .iter()
            .find(|h| matches!(&h.hint, Hint::Place(p) if p.zone.as_deref() == Some("wing-left")))
            .expect("the left snug is read");
        assert_eq!(wing.subjects, vec![1, 2]);
        // A corner made in a zone "with" its pieces.
        let hints = read(
            "Make a little reading corner in the short arm of the L with the bookcase, the two beanbags and the rug.",
            &["bookcase", "beanbag", "beanbag", "rug", "desk"],
        );
        let arm = hints
            .iter()
            .find(|h| matches!(&h.hint, Hint::Place(p) if p.zone.as_deref() == Some("wing")))
            .expect("the short arm is read");
        assert_eq!(arm.subjects, vec![0, 1, 2, 3]);
        // "Goes near the front window", "right next to it".
        let hints = read(
            "The high table goes near the front window. The changing table on the left wall, with the nappy bin right next to it.",
            &["high table", "changing table", "nappy bin"],
        );
        assert!(
            hints
                .iter()
                .any(|h| h.subjects == vec![0] && h.hint == Hint::ByWindow)
        );
        assert!(hints
            .iter()
            .any(|h| h.subjects == vec![2] && h.hint == Hint::Relation(Relation::Near, vec![1])));
    }
    #[test]
    fn pods_said_again_of_every_desk_are_the_pods_first_read() {
        let mut cats = vec!["student desk"; 8];
        cats.push("teacher desk");
        let hints = read(
            "Group the eight student desks into two pods of four: in each pod two pairs of desks are pushed together back to back.",
            &cats,
        );
        let pods: Vec<&PromptHint> = hints
            .iter()
            .filter(|h| matches!(&h.hint, Hint::Formation(f) if f.shape == FormationShape::Pods))
            .collect();
        assert_eq!(pods[0].subjects, (0..8).collect::<Vec<_>>(), "{hints:?}");
        assert!(matches!(&pods[0].hint, Hint::Formation(f) if f.count == Some(2)));
        assert!(!pods.iter().any(|h| h.subjects.len() > 8), "{hints:?}");
    }

    #[test]
    fn the_window_nearest_the_door_is_read() {
        let hints = read(
            "The teacher's desk goes under the window nearest the door, with the teacher's chair at it. The bookcase by the window.",
            &["teacher desk", "chair", "bookcase"],
        );
        assert!(
            hints
                .iter()
                .any(|h| h.subjects == vec![0] && h.hint == Hint::WindowByDoor)
        );
        assert!(
            !hints
                .iter()
                .any(|h| h.subjects == vec![2] && h.hint == Hint::WindowByDoor)
        );
    }
    proptest::proptest! {
        /// Any prompt made of the grammar's own words and punctuation, in any order, is read
        /// without a panic (a clause cut short, a comma last, a count with nothing after it).
        #[test]
        fn any_arrangement_of_the_grammar_s_words_is_read(
            words in proptest::collection::vec(0usize..GRAMMAR_WORDS.len(), 0..40)
        ) {
            let prompt: Vec<&str> = words.iter().map(|&k| GRAMMAR_WORDS[k]).collect();
            let prompt = prompt.join(" ");
            let cats = ["chair", "chair", "table", "desk", "bench", "window seat", "stand", "rug"];
            let hints = read(&prompt, &cats);
            for h in &hints {
                proptest::prop_assert!(h.subjects.iter().all(|&s| s < cats.len()));
            }
            let _ = unread(&prompt, &cats);
        }
    }

    /// Words the reader gives a meaning to, and punctuation.
    const GRAMMAR_WORDS: [&str; 58] = [
        "the",
        "a",
        "two",
        "four",
        "each",
        "every",
        "chair",
        "chairs",
        "table",
        "desk",
        "desks",
        "bench",
        "stand",
        "stands",
        "rug",
        "window",
        "door",
        "wall",
        "in",
        "on",
        "at",
        "by",
        "under",
        "against",
        "front",
        "of",
        "row",
        "rows",
        "columns",
        "pods",
        "facing",
        "face",
        "each other",
        "around",
        "between",
        "side",
        "end",
        "ends",
        "middle",
        "centred",
        "corner",
        "alcove",
        "snug",
        "to",
        "left",
        "right",
        "its",
        "with",
        "and",
        ",",
        ".",
        ";",
        "which",
        "nearest",
        "opposite",
        "back",
        "semicircle",
        "them",
    ];

    #[test]
    fn verbs_asides_and_relative_clauses_do_not_hide_a_place() {
        // "Stands" is a verb here, not the umbrella stand.
        let hints = read(
            "The wine rack stands against the end wall at the far end from the door.",
            &["wine rack", "umbrella stand"],
        );
        assert!(!hints.iter().any(|h| h.subjects.contains(&1)), "{hints:?}");
        // Past a short aside between commas, and in a clause said after a comma.
        let hints = read(
            "The two foam mats should be laid side by side, edges touching, in the middle of the floor. The two trestle tables, which should sit against the entrance wall.",
            &["mat", "mat", "trestle table", "trestle table"],
        );
        assert!(
            hints
                .iter()
                .any(|h| h.subjects == vec![0, 1] && h.hint == Hint::Centre)
        );
        assert!(
            hints
                .iter()
                .any(|h| h.subjects == vec![1]
                    && h.hint == Hint::Relation(Relation::SideOf, vec![0]))
        );
        assert!(hints.iter().any(|h| h.subjects == vec![2, 3]
            && matches!(&h.hint, Hint::Place(p) if p.wall == Some(WallRole::Entrance))));
    }

    #[test]
    fn more_ways_to_say_where_are_read() {
        let hints = read(
            "Two armchairs in the bay, turned to face each other with the little side table in between them. A reading armchair either side of the window. Put a shoe rack on each side of the door. The bookshelves on the end wall to the left.",
            &[
                "armchair",
                "armchair",
                "side table",
                "reading armchair",
                "shoe rack",
                "bookshelf",
            ],
        );
        let has = |subjects: &[usize], want: &dyn Fn(&Hint) -> bool| {
            hints
                .iter()
                .any(|h| h.subjects == subjects && want(&h.hint))
        };
        assert!(
            has(&[1], &|h| matches!(h, Hint::FacingEachOther(0))),
            "{hints:?}"
        );
        assert!(has(&[2], &|h| matches!(h, Hint::Between(_))), "{hints:?}");
        assert!(has(&[3], &|h| *h == Hint::ByWindow), "{hints:?}");
        assert!(
            has(&[4], &|h| matches!(h, Hint::Place(p) if p.by_entrance)),
            "{hints:?}"
        );
        assert!(has(
            &[5],
            &|h| matches!(h, Hint::Place(p) if p.wall == Some(WallRole::Left))
        ));
        // A piece named by its description's word before its head noun.
        let mut s = scene(
            "The patient chair goes in the middle of the floor.",
            &["dental chair", "side chair"],
        );
        s.assets[0].description = Some("patient chair, reclines flat".into());
        let hints = read_hints(&s, &Knowledge::builtin());
        assert!(
            hints
                .iter()
                .any(|h| h.subjects == vec![0] && h.hint == Hint::Centre),
            "{hints:?}"
        );
    }

    #[test]
    fn a_wall_s_middle_and_the_door_s_window_are_the_piece_s_own() {
        let hints = read(
            "The sofa faces the TV in the middle of the back wall. The coffee table centred on the sofa. That stand goes by the door.",
            &["sofa", "tv", "coffee table", "stand"],
        );
        let centred: Vec<&PromptHint> = hints
            .iter()
            .filter(|h| h.hint == Hint::CentredOnWall)
            .collect();
        assert!(centred.iter().all(|h| h.subjects == vec![1]), "{hints:?}");
        assert!(hints.iter().any(|h| h.subjects.contains(&3)), "{hints:?}");
    }
}
