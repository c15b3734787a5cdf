#!/usr/bin/env python3
"""Writes the benchmark set of real rooms (bench/rooms/*.json): floor plans that are not plain
rectangles (L, U and T shapes, rooms with a slanted wall), each with one or two doors and one or two
windows, across the nine room categories of bench/scenes plus room types the rules were not
written for.

Run from the repository root: `python3 bench/make_rooms.py`. The JSON files are committed; this
script is how they were made and how to change them consistently.

The room format is docs/formats.md, "Rooms": the outline's vertices counter-clockwise in cm, the
bounding box's bottom-left corner at the origin; wall `i` runs from vertex `i` to vertex `i + 1`;
an opening's `at` is the distance from its wall's start vertex to its centre. Furniture sizes come
from the catalogue of bench/make_scenes.py. Sills: 90 cm in living spaces, 100 cm above kitchen
counters and in gyms, 110-140 cm in bathrooms and laundries (the usual heights for privacy and for
worktops under the window).
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_scenes import CATALOGUE  # noqa: E402

# Sizes of the furniture that only the new room types use.
EXTRA = {
    "reception desk": [180, 70, 105], "waiting chair": [55, 60, 85], "magazine rack": [50, 30, 110],
}


# Outlines. Each returns the vertices counter-clockwise; the comment lists the walls in order.

def l_shape(w, d, cut_w, cut_d):
    """A w x d rectangle without its top-right cut_w x cut_d corner.
    Walls: 0 bottom, 1 right, 2 inner step (running -x), 3 inner side (running +y), 4 top, 5 left."""
    return [[0, 0], [w, 0], [w, d - cut_d], [w - cut_w, d - cut_d], [w - cut_w, d], [0, d]]


def l_shape_low(w, d, cut_w, cut_d):
    """A w x d rectangle without its bottom-left cut_w x cut_d corner.
    Walls: 0 inner step (running +x), 1 inner side (running -y), 2 bottom, 3 right, 4 top, 5 left."""
    return [[0, cut_d], [cut_w, cut_d], [cut_w, 0], [w, 0], [w, d], [0, d]]


def u_shape(w, d, notch_x, notch_w, notch_d):
    """A w x d rectangle with a notch notch_w wide and notch_d deep cut into its top side at notch_x.
    Walls: 0 bottom, 1 right, 2 top right, 3 notch right side (running -y), 4 notch floor (running -x),
    5 notch left side (running +y), 6 top left, 7 left."""
    return [[0, 0], [w, 0], [w, d], [notch_x + notch_w, d], [notch_x + notch_w, d - notch_d],
            [notch_x, d - notch_d], [notch_x, d], [0, d]]


def t_shape(w, d, stem_x, stem_w, stem_d):
    """A w-wide bar on top of a stem_w-wide, stem_d-deep stem at stem_x; the whole is d deep.
    Walls: 0 stem bottom, 1 stem right, 2 bar underside right, 3 right, 4 top, 5 left,
    6 bar underside left, 7 stem left (running -y)."""
    return [[stem_x, 0], [stem_x + stem_w, 0], [stem_x + stem_w, stem_d], [w, stem_d], [w, d],
            [0, d], [0, stem_d], [stem_x, stem_d]]


def slanted(w, d, cut_w, cut_d):
    """A w x d rectangle with its top-right corner cut by a slanted wall.
    Walls: 0 bottom, 1 right, 2 slanted, 3 top, 4 left."""
    return [[0, 0], [w, 0], [w, d - cut_d], [w - cut_w, d], [0, d]]


def trapezoid(w_bottom, w_top, d):
    """Bottom w_bottom wide, top w_top wide, left wall straight, right wall slanted.
    Walls: 0 bottom, 1 slanted right, 2 top, 3 left."""
    return [[0, 0], [w_bottom, 0], [w_top, d], [0, d]]


def hexagon(w, d, chamfer):
    """A w x d rectangle with both top corners cut at 45 degrees by chamfer.
    Walls: 0 bottom, 1 right, 2 slanted right, 3 top, 4 slanted left, 5 left."""
    return [[0, 0], [w, 0], [w, d - chamfer], [w - chamfer, d], [chamfer, d], [0, d - chamfer]]


def rect(w, d):
    """A plain rectangle (written as width and depth). Walls: 0 bottom, 1 right, 2 top, 3 left."""
    return (w, d)


def door(wall, at, width, swing="in", hinge="left"):
    return {"wall": wall, "at": at, "width": width, "swing": swing, "hinge": hinge}


def window(wall, at, width, sill=90, height=120):
    return {"wall": wall, "at": at, "width": width, "sill": sill, "height": height}


# id, category, prompt, outline, doors, windows, [(catalogue name, count), ...]
ROOMS = [
    # bedrooms
    ("bedroom-l-01", "bedroom", "an L-shaped bedroom with the door near the corner and a window on the long side",
     l_shape(480, 420, 160, 140), [door(0, 400, 80, hinge="right")], [window(5, 210, 140)],
     [("queen bed", 1), ("nightstand", 2), ("wardrobe", 1), ("dresser", 1), ("armchair", 1), ("floor lamp", 1), ("rug", 1)]),
    ("bedroom-slant-02", "bedroom", "a bedroom with one slanted wall, a desk and a wardrobe",
     slanted(420, 380, 120, 120), [door(3, 60, 80)], [window(2, 85, 100), window(0, 210, 120)],
     [("queen bed", 1), ("nightstand", 2), ("wardrobe", 1), ("desk", 1), ("office chair", 1), ("floor lamp", 1)]),
    ("bedroom-l-03", "bedroom", "a master bedroom with a king bed, a door to the en-suite and two windows",
     l_shape_low(560, 480, 180, 160), [door(5, 160, 85), door(2, 80, 80, swing="out")],
     [window(4, 280, 180, sill=80), window(3, 160, 120)],
     [("king bed", 1), ("nightstand", 2), ("bench", 1), ("dresser", 1), ("wardrobe", 2), ("vanity table", 1),
      ("vanity stool", 1), ("armchair", 1), ("floor lamp", 1), ("tv stand", 1), ("rug", 1)]),
    ("bedroom-rect-04", "bedroom", "a bedroom with the door on the left and a window opposite the bed",
     rect(380, 350), [door(3, 280, 80)], [window(1, 175, 120)],
     [("queen bed", 1), ("nightstand", 2), ("wardrobe", 1), ("chest of drawers", 1)]),
    # living rooms
    ("living-room-l-01", "living room", "an L-shaped living room with a sofa facing the TV",
     l_shape(620, 520, 240, 220), [door(5, 150, 90)], [window(0, 310, 200), window(1, 150, 160)],
     [("sofa", 1), ("coffee table", 1), ("media console", 1), ("armchair", 2), ("side table", 1), ("floor lamp", 1),
      ("bookshelf", 1), ("potted plant", 1), ("area rug", 1)]),
    ("living-room-u-02", "living room", "a U-shaped family room with a sectional, a fireplace and a piano",
     u_shape(700, 520, 220, 260, 180), [door(0, 560, 90), door(7, 100, 80, swing="out")],
     [window(2, 110, 140), window(6, 110, 140), window(1, 260, 180)],
     [("sectional sofa", 1), ("coffee table", 1), ("fireplace", 1), ("piano", 1), ("armchair", 2), ("side table", 2),
      ("floor lamp", 2), ("bookshelf", 2), ("ottoman", 1), ("potted plant", 2), ("area rug", 1), ("media console", 1)]),
    ("living-room-slant-03", "living room", "a small apartment living room with a slanted wall",
     slanted(400, 360, 140, 120), [door(4, 70, 85)], [window(0, 200, 160, sill=85), window(2, 92, 100)],
     [("loveseat", 1), ("coffee table", 1), ("tv stand", 1), ("armchair", 1), ("floor lamp", 1), ("potted plant", 1),
      ("side table", 1)]),
    ("living-room-rect-04", "living room", "a living room with two doors and a wide window",
     rect(450, 400), [door(0, 80, 85), door(3, 100, 80, swing="sliding")], [window(2, 225, 220)],
     [("sofa", 1), ("coffee table", 1), ("tv stand", 1), ("armchair", 1), ("bookshelf", 1), ("area rug", 1)]),
    # dining rooms
    ("dining-room-l-01", "dining room", "an L-shaped dining room for six with a sideboard",
     l_shape(520, 460, 180, 160), [door(0, 440, 90, hinge="right")], [window(4, 170, 180), window(1, 150, 120)],
     [("dining table", 1), ("dining chair", 6), ("sideboard", 1), ("china cabinet", 1), ("potted plant", 1)]),
    ("dining-room-slant-02", "dining room", "a dining room with a slanted wall and a round table for four",
     trapezoid(480, 400, 400), [door(3, 80, 85)], [window(2, 200, 160)],
     [("round dining table", 1), ("dining chair", 4), ("china cabinet", 1), ("bar cart", 1), ("potted plant", 1),
      ("area rug", 1)]),
    ("dining-room-t-03", "dining room", "a T-shaped formal dining room seating eight, entered through double doors",
     t_shape(600, 560, 150, 300, 180), [door(0, 150, 120)], [window(4, 300, 240), window(3, 190, 140)],
     [("dining table", 1), ("dining chair", 8), ("sideboard", 1), ("china cabinet", 1), ("bar cart", 1),
      ("potted plant", 2), ("large rug", 1), ("floor lamp", 1)]),
    # kitchens
    ("kitchen-l-01", "kitchen", "an L-shaped kitchen with a small table",
     l_shape(460, 400, 200, 200), [door(3, 120, 85)], [window(4, 130, 120, sill=100), window(0, 230, 100, sill=100)],
     [("refrigerator", 1), ("stove", 1), ("dishwasher", 1), ("kitchen sink", 1), ("kitchen counter", 2), ("pantry", 1),
      ("trash can", 1), ("kitchen table", 1), ("dining chair", 2)]),
    ("kitchen-slant-02", "kitchen", "a galley kitchen whose end wall is slanted",
     slanted(440, 260, 60, 80), [door(4, 130, 80)], [window(3, 190, 120, sill=100)],
     [("refrigerator", 1), ("stove", 1), ("kitchen sink", 1), ("kitchen counter", 2), ("dishwasher", 1),
      ("trash can", 1), ("microwave cart", 1)]),
    ("kitchen-l-03", "kitchen", "a large family kitchen with an island, stools, a pantry and a back door",
     l_shape_low(600, 480, 180, 160), [door(5, 160, 90), door(0, 90, 80, swing="out")],
     [window(2, 210, 150, sill=100), window(4, 300, 180, sill=100)],
     [("refrigerator", 1), ("stove", 1), ("dishwasher", 1), ("kitchen sink", 1), ("kitchen counter", 3), ("pantry", 2),
      ("kitchen island", 1), ("bar stool", 4), ("kitchen table", 1), ("dining chair", 4), ("trash can", 1),
      ("microwave cart", 1)]),
    # bathrooms
    ("bathroom-l-01", "bathroom", "an L-shaped bathroom with a bathtub",
     l_shape(320, 280, 120, 120), [door(0, 270, 80, hinge="right")], [window(4, 100, 80, sill=120, height=80)],
     [("bathtub", 1), ("toilet", 1), ("sink vanity", 1), ("towel rack", 1), ("laundry basket", 1), ("bath mat", 1)]),
    ("bathroom-slant-02", "bathroom", "an attic bathroom with a slanted wall and a washing machine",
     slanted(300, 240, 80, 90), [door(4, 160, 75)], [window(2, 60, 60, sill=140, height=60)],
     [("toilet", 1), ("sink vanity", 1), ("shower stall", 1), ("washing machine", 1), ("bathroom cabinet", 1),
      ("laundry basket", 1)]),
    ("bathroom-u-03", "bathroom", "a spacious master bathroom around a chimney breast, with a tub, a shower and a bidet",
     u_shape(460, 380, 150, 160, 100), [door(0, 380, 80)], [window(1, 190, 100, sill=120, height=90)],
     [("bathtub", 1), ("shower stall", 1), ("toilet", 1), ("bidet", 1), ("sink vanity", 2), ("bathroom cabinet", 2),
      ("towel rack", 2), ("laundry basket", 1), ("stool", 1), ("potted plant", 1), ("bath mat", 2)]),
    # children's rooms
    ("childrens-room-l-01", "children's room", "an L-shaped kids room with a play table and two small chairs",
     l_shape(420, 380, 140, 140), [door(0, 360, 80)], [window(4, 140, 120)],
     [("kids bed", 1), ("nightstand", 1), ("play table", 1), ("kids chair", 2), ("toy chest", 1), ("bookshelf", 1),
      ("wardrobe", 1), ("play mat", 1)]),
    ("childrens-room-slant-02", "children's room", "a nursery under a slanted wall with a crib and a rocking chair",
     slanted(360, 330, 120, 130), [door(4, 70, 80)], [window(0, 180, 120)],
     [("crib", 1), ("armchair", 1), ("chest of drawers", 1), ("toy chest", 1), ("floor lamp", 1),
      ("rocking horse", 1), ("play mat", 1)]),
    ("childrens-room-u-03", "children's room", "a big U-shaped room for two children with a play area and storage",
     u_shape(540, 460, 160, 220, 100), [door(0, 270, 85)], [window(2, 80, 100), window(6, 80, 100)],
     [("single bed", 2), ("nightstand", 2), ("wardrobe", 2), ("play table", 1), ("kids chair", 3), ("toy chest", 2),
      ("bookshelf", 2), ("teepee tent", 1), ("play mat", 1), ("study desk", 1), ("office chair", 1)]),
    # classrooms
    ("classroom-l-01", "classroom", "an L-shaped classroom with two doors and windows along two walls",
     l_shape(800, 640, 240, 180), [door(5, 100, 95), door(0, 720, 95, hinge="right")],
     [window(1, 230, 300), window(4, 280, 300)],
     [("whiteboard", 1), ("teacher desk", 1), ("office chair", 1), ("student desk", 8), ("student chair", 8),
      ("bookshelf", 1)]),
    ("classroom-slant-02", "classroom", "a classroom with a slanted back corner, desks facing the board",
     slanted(700, 560, 140, 160), [door(3, 480, 95)], [window(0, 350, 400)],
     [("whiteboard", 1), ("teacher desk", 1), ("office chair", 1), ("student desk", 9), ("student chair", 9),
      ("trash can", 1)]),
    ("classroom-t-03", "classroom", "a T-shaped seminar room entered through a short corridor",
     t_shape(650, 560, 200, 250, 200), [door(0, 125, 95)], [window(4, 325, 300), window(3, 180, 160)],
     [("whiteboard", 1), ("teacher desk", 1), ("office chair", 1), ("student desk", 6), ("student chair", 6),
      ("potted plant", 1), ("filing cabinet", 1)]),
    # buffet restaurants
    ("buffet-restaurant-l-01", "buffet restaurant", "an L-shaped buffet restaurant with double entrance doors and a kitchen door",
     l_shape(1000, 800, 400, 300), [door(0, 850, 180, swing="out"), door(5, 150, 90)],
     [window(4, 300, 400), window(1, 250, 300)],
     [("buffet counter", 2), ("drink station", 1), ("dessert station", 1), ("round table", 3), ("dining chair", 12),
      ("host stand", 1), ("potted plant", 1)]),
    ("buffet-restaurant-u-02", "buffet restaurant", "a U-shaped buffet hall with counters along the walls and round tables",
     u_shape(1100, 800, 300, 500, 200), [door(0, 550, 180, swing="out")], [window(2, 150, 200), window(6, 150, 200)],
     [("buffet counter", 3), ("salad bar", 1), ("drink station", 1), ("round table", 4), ("dining chair", 14),
      ("host stand", 1), ("trash can", 1)]),
    ("buffet-restaurant-slant-03", "buffet restaurant", "a hotel breakfast room with one slanted glass wall and long tables",
     slanted(900, 700, 250, 250), [door(4, 350, 160, swing="out")],
     [window(2, 177, 200), window(3, 325, 300)],
     [("buffet counter", 2), ("dessert station", 1), ("drink station", 1), ("banquet table", 3), ("dining chair", 16),
      ("tray return cart", 1)]),
    # home gyms
    ("home-gym-l-01", "home gym", "an L-shaped home gym with cardio machines and a mirror",
     l_shape(560, 480, 200, 180), [door(5, 400, 85)], [window(4, 180, 160, sill=100)],
     [("treadmill", 1), ("exercise bike", 1), ("elliptical", 1), ("wall mirror", 1), ("weight bench", 1),
      ("dumbbell rack", 1), ("fan", 1), ("gym mat", 1)]),
    ("home-gym-slant-02", "home gym", "a garage gym with a sliding garage door, a side door and a slanted wall",
     slanted(600, 550, 120, 150), [door(0, 300, 240, swing="sliding"), door(4, 100, 80)],
     [window(2, 96, 100, sill=110)],
     [("squat rack", 1), ("weight bench", 1), ("dumbbell rack", 1), ("rowing machine", 1), ("punching bag", 1),
      ("storage cabinet", 1), ("gym mat", 1)]),
    ("home-gym-t-03", "home gym", "a complete T-shaped home gym",
     t_shape(750, 600, 250, 250, 200), [door(0, 125, 90)], [window(4, 375, 240, sill=100)],
     [("treadmill", 2), ("exercise bike", 1), ("rowing machine", 1), ("elliptical", 1), ("squat rack", 1),
      ("weight bench", 2), ("dumbbell rack", 2), ("wall mirror", 2), ("punching bag", 1), ("fan", 1),
      ("storage cabinet", 1), ("gym mat", 1)]),
    # room types the rules were not written for
    ("office-l-01", "office", "an L-shaped open office with a meeting table",
     l_shape(900, 700, 300, 300), [door(5, 600, 95), door(2, 150, 90)], [window(0, 450, 400), window(4, 300, 300)],
     [("desk", 6), ("office chair", 6), ("meeting table", 1), ("conference chair", 6), ("filing cabinet", 2),
      ("printer stand", 1), ("water cooler", 1), ("potted plant", 1)]),
    ("library-u-01", "library", "a U-shaped library with bookcases along the walls and reading tables",
     u_shape(900, 650, 250, 400, 200), [door(0, 450, 160, swing="out")],
     [window(2, 125, 150, sill=100), window(6, 125, 150, sill=100)],
     [("bookcase", 8), ("reading table", 2), ("dining chair", 8), ("reading chair", 2), ("librarian desk", 1),
      ("office chair", 1), ("globe stand", 1)]),
    ("laundry-slant-01", "laundry room", "a laundry room with a slanted wall",
     slanted(380, 280, 100, 100), [door(4, 200, 80)], [window(2, 70, 70, sill=110, height=80)],
     [("washer", 1), ("dryer", 1), ("utility sink", 1), ("ironing board", 1), ("folding table", 1), ("drying rack", 1),
      ("laundry basket", 2), ("shelving unit", 1)]),
    ("studio-l-01", "studio apartment", "an L-shaped studio apartment with a bed, a sofa and a kitchenette",
     l_shape(620, 560, 220, 180), [door(0, 540, 90, hinge="right")], [window(4, 200, 200), window(1, 190, 140)],
     [("queen bed", 1), ("nightstand", 1), ("wardrobe", 1), ("sofa", 1), ("coffee table", 1), ("tv stand", 1),
      ("kitchen counter", 1), ("refrigerator", 1), ("stove", 1), ("kitchen table", 1), ("dining chair", 2),
      ("floor lamp", 1), ("area rug", 1)]),
    ("waiting-room-01", "waiting room", "a waiting room with two slanted corners and a reception desk",
     hexagon(600, 450, 150), [door(0, 300, 100)], [window(3, 150, 200)],
     [("reception desk", 1), ("office chair", 1), ("waiting chair", 8), ("coffee table", 1), ("potted plant", 2),
      ("magazine rack", 1), ("water cooler", 1)]),
]


def size_of(category):
    return CATALOGUE.get(category) or EXTRA[category]


def room_json(outline, doors, windows):
    if isinstance(outline, tuple):
        room = {"width": outline[0], "depth": outline[1]}
    else:
        room = {"polygon": outline}
    if doors:
        room["doors"] = doors
    if windows:
        room["windows"] = windows
    return room


def scene(sid, room_type, prompt, outline, doors, windows, items):
    assets = []
    for cat, count in items:
        for i in range(count):
            assets.append({"name": f"{cat}-{i}", "category": cat, "size": size_of(cat)})
    assert 5 <= len(assets) <= 25, f"{sid}: {len(assets)} assets"
    return {"id": sid, "prompt": prompt, "room_type": room_type,
            "room": room_json(outline, doors, windows), "assets": assets}


def main():
    directory = "bench/rooms"
    os.makedirs(directory, exist_ok=True)
    for s in ROOMS:
        with open(os.path.join(directory, s[0] + ".json"), "w", encoding="utf-8") as f:
            json.dump(scene(*s), f, indent=1)
            f.write("\n")
    print(f"wrote {len(ROOMS)} rooms to {directory}")


if __name__ == "__main__":
    main()
