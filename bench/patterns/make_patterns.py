#!/usr/bin/env python3
"""Writes the arrangement test set: one scene JSON per entry below and `expect.toml`, the
pattern each scene's prompt names and the objects it applies to (read by
`src/bench/patterns.rs`). Run from the repository root: python3 bench/patterns/make_patterns.py

The scenes stay plain `disco validate` input; the expectations live beside them, never in them.
"""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))


class Scene:
    def __init__(self, sid, room_type, prompt, width, depth):
        self.sid, self.room_type, self.prompt = sid, room_type, prompt
        self.width, self.depth = width, depth
        self.assets, self.counts, self.expect = [], {}, {}

    def add(self, category, w, d, h, count=1):
        names = []
        for _ in range(count):
            i = self.counts.get(category, 0)
            self.counts[category] = i + 1
            name = f"{category}-{i}"
            self.assets.append({"name": name, "category": category, "size": [w, d, h]})
            names.append(name)
        return names

    def json(self):
        return {"id": self.sid, "prompt": self.prompt, "room_type": self.room_type,
                "room": {"width": self.width, "depth": self.depth}, "assets": self.assets}


def toml_value(v):
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, str):
        return json.dumps(v)
    return repr(v)


SCENES = []


def scene(sid, room_type, prompt, width, depth):
    s = Scene(sid, room_type, prompt, width, depth)
    SCENES.append(s)
    return s


def kitchen_run(s, dishwasher=True, counters=1):
    fridge = s.add("refrigerator", 80, 70, 180)[0]
    stove = s.add("stove", 60, 60, 90)[0]
    sink = s.add("sink cabinet", 80, 60, 90)[0]
    dw = s.add("dishwasher", 60, 60, 85)[0] if dishwasher else None
    counter = s.add("kitchen counter", 100, 60, 90, counters)
    return fridge, stove, sink, dw, counter


# --- rows facing a focal wall -------------------------------------------------------------
s = scene("rows-classroom", "classroom", "a classroom with rows of student desks all facing the whiteboard", 700, 600)
board = s.add("whiteboard", 240, 10, 120)[0]
s.add("teacher desk", 140, 70, 75); s.add("office chair", 60, 60, 100)
desks = s.add("student desk", 70, 50, 75, 12); chairs = s.add("student chair", 40, 45, 80, 12)
s.expect = dict(pattern="rows", focal=board, members=desks, seats=chairs)

s = scene("rows-lecture", "lecture room", "small lecture hall: line the school desks up in rows so every student looks at the projector screen", 800, 650)
screen = s.add("projector screen", 300, 10, 200)[0]
s.add("lectern", 60, 50, 110)
desks = s.add("school desk", 120, 50, 75, 8); chairs = s.add("school chair", 45, 45, 80, 8)
s.expect = dict(pattern="rows", focal=screen, members=desks, seats=chairs)

s = scene("rows-cinema", "home cinema", "a home cinema with three rows of recliners facing the big screen", 600, 750)
screen = s.add("projector screen", 320, 10, 180)[0]
rec = s.add("recliner", 90, 95, 100, 9)
s.add("side table", 40, 40, 50)
s.expect = dict(pattern="rows", focal=screen, members=rec, seats=rec)

# --- U / horseshoe --------------------------------------------------------------------------
s = scene("u-seminar", "seminar room", "a seminar room where student desks form a U shape facing the projector screen", 800, 700)
screen = s.add("projector screen", 280, 10, 180)[0]
desks = s.add("student desk", 120, 50, 75, 8); chairs = s.add("student chair", 45, 45, 80, 8)
s.expect = dict(pattern="u_shape", focal=screen, members=desks, seats=chairs)

s = scene("u-workshop", "training room", "training room, tables set out as a horseshoe that opens towards the whiteboard", 750, 650)
board = s.add("whiteboard", 240, 10, 120)[0]
tables = s.add("training table", 140, 60, 75, 7); chairs = s.add("conference chair", 55, 55, 90, 7)
s.expect = dict(pattern="u_shape", focal=board, members=tables, seats=chairs)

# --- L --------------------------------------------------------------------------------------
s = scene("l-kitchen", "kitchen", "an L-shaped kitchen, the counters wrapping around one corner, with a small table for two", 450, 400)
f, st, sk, dw, c = kitchen_run(s, counters=2)
s.add("kitchen table", 90, 70, 75); s.add("dining chair", 45, 50, 90, 2)
s.expect = dict(pattern="l_shape", members=[f, st, sk, dw] + c)

s = scene("l-office", "home office", "a home office with two desks joined in an L shape in one corner", 420, 380)
desks = s.add("desk", 160, 70, 75) + s.add("desk", 140, 60, 75)
s.add("office chair", 60, 60, 100); s.add("bookshelf", 90, 35, 190)
s.expect = dict(pattern="l_shape", members=desks)

# --- island with stools ---------------------------------------------------------------------
s = scene("island-modern", "kitchen", "a modern kitchen with a central island surrounded by bar stools", 560, 460)
kitchen_run(s)
island = s.add("kitchen island", 200, 100, 90)[0]; stools = s.add("bar stool", 40, 40, 75, 3)
s.expect = dict(pattern="island", focal=island, seats=stools)

s = scene("island-open", "kitchen", "open-plan kitchen: fridge, stove and sink on the walls, an island in the middle with four counter stools", 620, 500)
kitchen_run(s, counters=2)
island = s.add("kitchen island", 240, 100, 90)[0]; stools = s.add("counter stool", 40, 40, 75, 4)
s.expect = dict(pattern="island", focal=island, seats=stools)

s = scene("island-bar", "kitchen", "kitchen where the breakfast bar stands free in the room with stools tucked in along it", 520, 500)
kitchen_run(s, dishwasher=False)
island = s.add("bar counter", 180, 60, 105)[0]; stools = s.add("bar stool", 40, 40, 75, 3)
s.expect = dict(pattern="island", focal=island, seats=stools)

# --- galley ---------------------------------------------------------------------------------
s = scene("galley-classic", "kitchen", "a galley kitchen", 520, 260)
f, st, sk, dw, c = kitchen_run(s, counters=2)
s.expect = dict(pattern="galley", members=[f, st, sk, dw] + c)

s = scene("galley-narrow", "kitchen", "narrow kitchen with two parallel counter runs facing each other across the aisle", 460, 250)
f, st, sk, dw, c = kitchen_run(s, counters=1)
pantry = s.add("pantry cabinet", 80, 60, 210)
s.expect = dict(pattern="galley", members=[f, st, sk, dw] + c + pantry)

# --- one-wall run ---------------------------------------------------------------------------
s = scene("onewall-kitchenette", "kitchen", "a studio kitchenette with every appliance in one line along a single wall, plus a little table", 430, 350)
f, st, sk, dw, c = kitchen_run(s)
s.add("kitchen table", 80, 80, 75); s.add("dining chair", 45, 50, 90, 2)
s.expect = dict(pattern="one_wall", members=[f, st, sk, dw] + c)

s = scene("onewall-laundry", "laundry room", "laundry room: washer, dryer and utility sink side by side on one wall", 360, 260)
m = s.add("washing machine", 60, 60, 85) + s.add("dryer", 60, 60, 85) + s.add("utility sink", 60, 55, 90)
s.add("storage cabinet", 80, 40, 180)
s.expect = dict(pattern="one_wall", members=m)

# --- kitchen work zone ----------------------------------------------------------------------
s = scene("workzone-dishwasher", "kitchen", "a kitchen where the dishwasher sits right next to the sink", 500, 400)
f, st, sk, dw, c = kitchen_run(s, counters=2)
s.expect = dict(pattern="work_zone", pair=[sk, dw])

s = scene("workzone-triangle", "kitchen", "family kitchen with a tight work triangle between fridge, stove and sink, dishwasher beside the sink", 560, 460)
f, st, sk, dw, c = kitchen_run(s, counters=2)
s.add("dining table", 160, 90, 75); s.add("dining chair", 45, 50, 90, 4)
s.expect = dict(pattern="work_zone", pair=[sk, dw], triangle=[f, st, sk])

s = scene("workzone-compact", "kitchen", "compact kitchen, please put the dishwasher beside the sink", 400, 300)
f, st, sk, dw, c = kitchen_run(s)
s.expect = dict(pattern="work_zone", pair=[sk, dw])

# --- around a centre piece ------------------------------------------------------------------
s = scene("around-dining", "dining room", "a dining room with eight chairs around the dining table and a sideboard", 600, 460)
t = s.add("dining table", 220, 100, 75)[0]; ch = s.add("dining chair", 45, 50, 90, 8)
s.add("sideboard", 160, 45, 85)
s.expect = dict(pattern="around", focal=t, members=ch)

s = scene("around-poker", "game room", "a game room with stools gathered around a round poker table", 520, 460)
t = s.add("round table", 130, 130, 75)[0]; ch = s.add("stool", 40, 40, 70, 5)
s.add("bookshelf", 90, 35, 190); s.add("sofa", 200, 90, 85)
s.expect = dict(pattern="around", focal=t, members=ch)

s = scene("around-firepit", "lounge", "a cosy lounge with four armchairs arranged around the fire pit", 560, 500)
t = s.add("fire pit", 100, 100, 40)[0]; ch = s.add("armchair", 85, 85, 95, 4)
s.add("bookshelf", 90, 35, 190)
s.expect = dict(pattern="around", focal=t, members=ch)

# --- in a corner ----------------------------------------------------------------------------
s = scene("corner-meeting", "office", "an office with a meeting table in the corner", 620, 500)
t = s.add("meeting table", 160, 90, 75)[0]; s.add("conference chair", 55, 55, 90, 4)
s.add("desk", 160, 70, 75); s.add("office chair", 60, 60, 100); s.add("bookshelf", 90, 35, 190)
s.expect = dict(pattern="corner", focal=t, within=70)

s = scene("corner-reading", "living room", "a living room with the reading chair in a corner and a floor lamp next to it", 520, 450)
s.add("sofa", 220, 95, 85); s.add("coffee table", 110, 60, 45); s.add("tv stand", 180, 45, 55)
chair = s.add("reading chair", 80, 85, 100)[0]; s.add("floor lamp", 40, 40, 160)
s.expect = dict(pattern="corner", focal=chair, within=30)

s = scene("corner-desk", "bedroom", "a teenager's bedroom: bed with a nightstand, a wardrobe, and the desk tucked into the corner", 450, 420)
s.add("single bed", 100, 200, 60); s.add("nightstand", 45, 40, 55); s.add("wardrobe", 120, 60, 200)
d = s.add("desk", 120, 60, 75)[0]; s.add("office chair", 60, 60, 100)
s.expect = dict(pattern="corner", focal=d, within=30)

# --- centred / freestanding -----------------------------------------------------------------
s = scene("centred-spa", "bathroom", "a spa-like bathroom with a freestanding tub in the middle, double vanity along one wall and a walk-in shower corner", 500, 420)
tub = s.add("bathtub", 170, 80, 60)[0]
fixtures = s.add("double vanity", 150, 55, 85) + s.add("toilet", 40, 70, 80) + s.add("shower", 100, 100, 210)
s.expect = dict(pattern="centred", focal=tub, on_wall=fixtures)

s = scene("centred-bed", "bedroom", "a loft bedroom where the bed stands free in the centre of the room, wardrobe and dresser against the walls", 560, 500)
bed = s.add("bed", 160, 210, 100)[0]
fixtures = s.add("wardrobe", 150, 60, 210) + s.add("dresser", 120, 50, 90)
s.expect = dict(pattern="centred", focal=bed, on_wall=fixtures)

s = scene("centred-desk", "office", "an executive office: the big desk sits in the middle of the room, filing cabinets and a bookcase on the walls", 560, 480)
d = s.add("executive desk", 180, 85, 76)[0]; s.add("office chair", 65, 65, 110)
fixtures = s.add("filing cabinet", 50, 60, 130, 2) + s.add("bookcase", 100, 35, 200)
s.expect = dict(pattern="centred", focal=d, on_wall=fixtures)

# --- symmetric pair -------------------------------------------------------------------------
s = scene("pair-nightstands", "bedroom", "a master bedroom with a nightstand on each side of the bed", 500, 450)
bed = s.add("bed", 180, 210, 100)[0]; ns = s.add("nightstand", 50, 40, 55, 2)
s.add("wardrobe", 150, 60, 210); s.add("dresser", 120, 50, 90)
s.expect = dict(pattern="symmetric_pair", focal=bed, pair=ns)

s = scene("pair-endtables", "living room", "a living room with the sofa flanked by two matching end tables", 560, 460)
sofa = s.add("sofa", 220, 95, 85)[0]; et = s.add("end table", 50, 50, 55, 2)
s.add("coffee table", 110, 60, 45); s.add("tv stand", 180, 45, 55)
s.expect = dict(pattern="symmetric_pair", focal=sofa, pair=et)

s = scene("pair-guest", "bedroom", "guest room, twin bedside tables either side of the queen bed", 420, 400)
bed = s.add("queen bed", 160, 205, 100)[0]; ns = s.add("bedside table", 45, 40, 55, 2)
s.add("dresser", 100, 45, 85)
s.expect = dict(pattern="symmetric_pair", focal=bed, pair=ns)

# --- conversation set -----------------------------------------------------------------------
s = scene("conv-armchairs", "living room", "a living room where the sofa and two armchairs face each other across the coffee table", 560, 480)
sofa = s.add("sofa", 220, 95, 85); arm = s.add("armchair", 85, 85, 95, 2)
ct = s.add("coffee table", 110, 60, 45)[0]; s.add("bookshelf", 90, 35, 190)
s.expect = dict(pattern="conversation", focal=ct, seats=sofa + arm)

s = scene("conv-tv", "living room", "family room with the sofa facing the TV and nothing blocking the view of the screen", 540, 460)
sofa = s.add("sofa", 220, 95, 85); tv = s.add("tv stand", 180, 45, 55)[0]
s.add("coffee table", 110, 60, 45); s.add("armchair", 85, 85, 95); s.add("bookshelf", 90, 35, 190)
s.expect = dict(pattern="conversation", focal=tv, seats=sofa, screen=tv)

s = scene("conv-sofas", "lounge", "a lounge with two sofas facing each other and a coffee table between them", 600, 500)
sofas = s.add("sofa", 200, 90, 85, 2); ct = s.add("coffee table", 120, 60, 45)[0]
s.add("side table", 45, 45, 55); s.add("potted plant", 45, 45, 120)
s.expect = dict(pattern="conversation", focal=ct, seats=sofas)

# --- along a wall ---------------------------------------------------------------------------
s = scene("along-library", "library", "a reading room with bookshelves along the walls and a reading table with two chairs", 600, 500)
shelves = s.add("bookshelf", 100, 35, 200, 4)
s.add("table", 140, 80, 75); s.add("chair", 45, 50, 90, 2); s.add("armchair", 85, 85, 95)
s.expect = dict(pattern="along_wall", members=shelves)

s = scene("along-gym", "home gym", "home gym, the machines lined up against the walls and a yoga mat in the open floor", 620, 500)
m = s.add("exercise bike", 60, 120, 140) + s.add("rowing machine", 60, 240, 60) + s.add("weight rack", 120, 60, 150)
s.add("yoga mat", 180, 60, 1)
s.expect = dict(pattern="along_wall", members=m)


def main():
    for f in os.listdir(HERE):
        if f.endswith(".json"):
            os.remove(os.path.join(HERE, f))
    lines = ["# What each scene of bench/patterns asks for: the arrangement its prompt names and the",
             "# objects it applies to. Written by make_patterns.py, read by src/bench/patterns.rs.", ""]
    for s in SCENES:
        with open(os.path.join(HERE, s.sid + ".json"), "w") as f:
            json.dump(s.json(), f, indent=1)
            f.write("\n")
        lines.append(f'[scene."{s.sid}"]')
        for k, v in s.expect.items():
            lines.append(f"{k} = {toml_value(v)}")
        lines.append("")
    with open(os.path.join(HERE, "expect.toml"), "w") as f:
        f.write("\n".join(lines))
    print(f"{len(SCENES)} scenes")


main()
