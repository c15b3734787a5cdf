#!/usr/bin/env python3
"""Writes the benchmark scenes (bench/scenes/*.json) from the catalogue and scene lists below.

Run from the repository root: `python3 bench/make_scenes.py`. The JSON files are committed; this
script is how they were made and how to change them consistently.

Dimensions are [width, depth, height] in cm, width along the object's front. They are typical
catalogue sizes of mass-market furniture (the common sizes of IKEA-class retailers' product sheets
and of standard references such as Neufert's *Architects' Data*: a queen bed 160 x 200 mattress in a
frame of about 170 x 215, dining chairs about 45 x 52, a standard kitchen base unit 60 deep and 90
high, a classroom student desk 70 x 50). They are rounded to 5 cm, since what matters here is
plausibility, not one product.
"""
import json
import os

CATALOGUE = {
    # bathroom
    "toilet": [40, 70, 78], "bathtub": [170, 75, 58], "shower stall": [90, 90, 200],
    "sink vanity": [80, 50, 85], "bathroom cabinet": [60, 30, 180], "towel rack": [60, 25, 100],
    "laundry basket": [40, 35, 60], "bath mat": [80, 50, 1], "washing machine": [60, 60, 85],
    "bidet": [40, 60, 40], "stool": [35, 35, 45],
    # bedroom
    "queen bed": [170, 215, 100], "king bed": [195, 215, 105], "single bed": [100, 205, 90],
    "nightstand": [50, 40, 55], "wardrobe": [120, 60, 200], "dresser": [120, 50, 80],
    "desk": [120, 60, 75], "office chair": [60, 60, 100], "armchair": [80, 80, 95],
    "floor lamp": [40, 40, 160], "rug": [200, 300, 1], "bench": [130, 40, 45],
    "bookshelf": [80, 30, 180], "potted plant": [40, 40, 120], "vanity table": [100, 45, 75],
    "vanity stool": [40, 35, 45], "tv stand": [150, 40, 50], "chest of drawers": [80, 45, 100],
    "laundry hamper": [40, 40, 60],
    # dining
    "dining table": [180, 90, 75], "round dining table": [120, 120, 75],
    "dining chair": [45, 52, 90], "sideboard": [160, 45, 80], "china cabinet": [100, 45, 190],
    "bar cart": [80, 45, 90], "large rug": [250, 300, 1],
    # kitchen
    "refrigerator": [70, 70, 180], "stove": [60, 60, 90], "dishwasher": [60, 60, 85],
    "kitchen sink": [80, 60, 90], "kitchen counter": [120, 60, 90], "kitchen island": [180, 90, 92],
    "bar stool": [40, 40, 75], "kitchen table": [120, 80, 75], "pantry": [80, 60, 200],
    "microwave cart": [60, 40, 90], "trash can": [35, 35, 65],
    # living room
    "sofa": [220, 95, 85], "loveseat": [150, 90, 85], "sectional sofa": [280, 160, 85],
    "coffee table": [110, 60, 45], "side table": [50, 50, 55], "ottoman": [60, 60, 45],
    "fireplace": [150, 50, 110], "piano": [150, 60, 120], "media console": [180, 45, 55],
    "area rug": [240, 170, 1],
    # restaurant
    "buffet counter": [240, 80, 90], "drink station": [150, 70, 100],
    "dessert station": [150, 70, 90], "round table": [120, 120, 75],
    "banquet table": [180, 90, 75], "host stand": [70, 50, 110], "high chair": [55, 60, 100],
    "salad bar": [200, 90, 90], "tray return cart": [90, 50, 120],
    # classroom
    "student desk": [70, 50, 75], "student chair": [40, 45, 80], "teacher desk": [140, 70, 75],
    "whiteboard": [240, 10, 120], "locker": [90, 45, 180], "projector cart": [60, 45, 90],
    "filing cabinet": [45, 60, 130],
    # children's room
    "kids bed": [100, 200, 80], "bunk bed": [100, 205, 160], "toy chest": [80, 45, 50],
    "play table": [80, 60, 50], "kids chair": [35, 35, 55], "play mat": [150, 150, 1],
    "teepee tent": [120, 120, 160], "rocking horse": [80, 30, 60], "crib": [70, 130, 95],
    "study desk": [100, 55, 70],
    # home gym
    "treadmill": [80, 190, 140], "exercise bike": [60, 120, 130], "rowing machine": [55, 230, 50],
    "weight bench": [60, 130, 45], "squat rack": [130, 140, 230], "dumbbell rack": [120, 50, 80],
    "yoga mat": [60, 180, 1], "wall mirror": [100, 5, 180], "punching bag": [45, 45, 150],
    "storage cabinet": [80, 45, 180], "fan": [45, 35, 110], "elliptical": [70, 180, 160],
    "gym mat": [200, 100, 2],
    # unseen room types
    "bookcase": [90, 35, 200], "reading table": [160, 80, 75], "reading chair": [75, 80, 95],
    "librarian desk": [160, 70, 75], "card catalogue": [90, 50, 130], "globe stand": [50, 50, 100],
    "washer": [60, 60, 85], "dryer": [60, 60, 85], "utility sink": [60, 55, 90],
    "ironing board": [120, 40, 90], "folding table": [120, 60, 75], "drying rack": [110, 55, 100],
    "shelving unit": [100, 40, 180], "meeting table": [240, 110, 75], "conference chair": [55, 55, 95],
    "printer stand": [60, 50, 80], "water cooler": [35, 35, 110],
}

# id, category, prompt, room [w, d], [(catalogue name, count), ...]
SCENES = [
    # bathrooms
    ("bathroom-01", "bathroom", "a bathroom", [250, 220],
     [("toilet", 1), ("sink vanity", 1), ("shower stall", 1), ("bath mat", 1)]),
    ("bathroom-02", "bathroom", "a family bathroom with a bathtub along the wall and a double vanity", [320, 280],
     [("bathtub", 1), ("toilet", 1), ("sink vanity", 2), ("towel rack", 1), ("laundry basket", 1), ("bath mat", 1)]),
    ("bathroom-03", "bathroom", "a tight bathroom with a shower, toilet and sink", [200, 180],
     [("shower stall", 1), ("toilet", 1), ("sink vanity", 1), ("towel rack", 1)]),
    ("bathroom-04", "bathroom", "a spacious master bathroom with a tub, a separate shower, a bidet and plenty of storage", [420, 350],
     [("bathtub", 1), ("shower stall", 1), ("toilet", 1), ("bidet", 1), ("sink vanity", 2), ("bathroom cabinet", 2),
      ("towel rack", 2), ("laundry basket", 1), ("stool", 1), ("potted plant", 1), ("bath mat", 2)]),
    ("bathroom-05", "bathroom", "a bathroom with a washing machine in the corner", [300, 240],
     [("toilet", 1), ("sink vanity", 1), ("shower stall", 1), ("washing machine", 1), ("bathroom cabinet", 1), ("laundry basket", 1)]),
    # bedrooms
    ("bedroom-01", "bedroom", "a bedroom", [380, 350],
     [("queen bed", 1), ("nightstand", 2), ("wardrobe", 1)]),
    ("bedroom-02", "bedroom", "a cozy bedroom with a reading corner", [420, 380],
     [("queen bed", 1), ("nightstand", 2), ("wardrobe", 1), ("armchair", 1), ("floor lamp", 1), ("side table", 1), ("rug", 1)]),
    ("bedroom-03", "bedroom", "a student bedroom with a desk by the wall and a bookshelf", [330, 300],
     [("single bed", 1), ("nightstand", 1), ("desk", 1), ("office chair", 1), ("bookshelf", 1), ("wardrobe", 1), ("laundry hamper", 1)]),
    ("bedroom-04", "bedroom", "a master bedroom with a king bed, a bench at its foot, a dresser facing the bed and a vanity", [520, 460],
     [("king bed", 1), ("nightstand", 2), ("bench", 1), ("dresser", 1), ("wardrobe", 2), ("vanity table", 1), ("vanity stool", 1),
      ("armchair", 1), ("floor lamp", 1), ("potted plant", 1), ("tv stand", 1), ("rug", 1)]),
    ("bedroom-05", "bedroom", "a small guest bedroom", [300, 280],
     [("queen bed", 1), ("nightstand", 2), ("chest of drawers", 1), ("floor lamp", 1)]),
    # dining rooms
    ("dining-room-01", "dining room", "a dining room", [420, 380],
     [("dining table", 1), ("dining chair", 6), ("sideboard", 1)]),
    ("dining-room-02", "dining room", "a dining room with a round table for four in the center", [360, 340],
     [("round dining table", 1), ("dining chair", 4), ("china cabinet", 1), ("potted plant", 1), ("area rug", 1)]),
    ("dining-room-03", "dining room", "a formal dining room seating eight, with a sideboard along the wall and a china cabinet", [520, 440],
     [("dining table", 1), ("dining chair", 8), ("sideboard", 1), ("china cabinet", 1), ("bar cart", 1), ("potted plant", 2), ("large rug", 1), ("floor lamp", 1)]),
    ("dining-room-04", "dining room", "a compact dining nook", [300, 280],
     [("kitchen table", 1), ("dining chair", 4), ("potted plant", 1)]),
    ("dining-room-05", "dining room", "a large dining room with two tables for a family gathering", [620, 480],
     [("dining table", 2), ("dining chair", 12), ("sideboard", 1), ("china cabinet", 1), ("bar cart", 1), ("potted plant", 2)]),
    # kitchens
    ("kitchen-01", "kitchen", "a kitchen", [360, 300],
     [("refrigerator", 1), ("stove", 1), ("kitchen sink", 1), ("kitchen counter", 1)]),
    ("kitchen-02", "kitchen", "a modern kitchen with a central island surrounded by bar stools", [480, 420],
     [("refrigerator", 1), ("stove", 1), ("dishwasher", 1), ("kitchen sink", 1), ("kitchen counter", 2), ("kitchen island", 1),
      ("bar stool", 4), ("pantry", 1), ("trash can", 1)]),
    ("kitchen-03", "kitchen", "a galley kitchen", [420, 240],
     [("refrigerator", 1), ("stove", 1), ("kitchen sink", 1), ("kitchen counter", 2), ("dishwasher", 1), ("trash can", 1)]),
    ("kitchen-04", "kitchen", "an eat-in kitchen with a small table and chairs", [450, 380],
     [("refrigerator", 1), ("stove", 1), ("kitchen sink", 1), ("kitchen counter", 2), ("kitchen table", 1), ("dining chair", 4),
      ("microwave cart", 1), ("potted plant", 1)]),
    ("kitchen-05", "kitchen", "a large family kitchen with an island, stools and a pantry", [560, 480],
     [("refrigerator", 1), ("stove", 1), ("dishwasher", 1), ("kitchen sink", 1), ("kitchen counter", 3), ("pantry", 2),
      ("kitchen island", 1), ("bar stool", 4), ("kitchen table", 1), ("dining chair", 4), ("trash can", 1), ("microwave cart", 1)]),
    # living rooms
    ("living-room-01", "living room", "a living room", [450, 400],
     [("sofa", 1), ("coffee table", 1), ("tv stand", 1), ("area rug", 1)]),
    ("living-room-02", "living room", "a living room with a sofa facing the TV and a coffee table in between", [520, 440],
     [("sofa", 1), ("coffee table", 1), ("media console", 1), ("armchair", 2), ("side table", 1), ("floor lamp", 1), ("bookshelf", 1),
      ("potted plant", 1), ("area rug", 1)]),
    ("living-room-03", "living room", "a family room with a sectional, a fireplace and a piano", [620, 500],
     [("sectional sofa", 1), ("coffee table", 1), ("fireplace", 1), ("piano", 1), ("armchair", 2), ("side table", 2),
      ("floor lamp", 2), ("bookshelf", 2), ("ottoman", 1), ("potted plant", 2), ("area rug", 1), ("media console", 1)]),
    ("living-room-04", "living room", "a small apartment living room", [380, 340],
     [("loveseat", 1), ("coffee table", 1), ("tv stand", 1), ("armchair", 1), ("floor lamp", 1), ("potted plant", 1)]),
    ("living-room-05", "living room", "a reading lounge with two armchairs around a coffee table and bookshelves along the walls", [480, 420],
     [("armchair", 2), ("coffee table", 1), ("bookshelf", 3), ("floor lamp", 2), ("side table", 2), ("sofa", 1), ("area rug", 1)]),
    # buffet restaurants
    ("buffet-restaurant-01", "buffet restaurant", "a buffet restaurant", [900, 700],
     [("buffet counter", 2), ("round table", 3), ("dining chair", 12), ("drink station", 1)]),
    ("buffet-restaurant-02", "buffet restaurant", "a buffet restaurant with buffet counters along the walls and round tables in the middle", [1200, 900],
     [("buffet counter", 3), ("salad bar", 1), ("dessert station", 1), ("drink station", 1), ("round table", 5), ("dining chair", 20),
      ("potted plant", 4), ("host stand", 1), ("trash can", 2)]),
    ("buffet-restaurant-03", "buffet restaurant", "a hotel breakfast buffet with long tables", [1000, 800],
     [("buffet counter", 2), ("drink station", 1), ("banquet table", 4), ("dining chair", 24), ("tray return cart", 1), ("potted plant", 2)]),
    ("buffet-restaurant-04", "buffet restaurant", "a small buffet cafe with a dessert station", [700, 600],
     [("buffet counter", 1), ("dessert station", 1), ("drink station", 1), ("round table", 3), ("dining chair", 12), ("high chair", 1), ("trash can", 1)]),
    ("buffet-restaurant-05", "buffet restaurant", "a large buffet restaurant with a salad bar, a dessert station and mixed seating", [1400, 1000],
     [("buffet counter", 3), ("salad bar", 1), ("dessert station", 1), ("drink station", 2), ("round table", 4), ("banquet table", 2),
      ("dining chair", 24), ("potted plant", 2), ("host stand", 1)]),
    # classrooms
    ("classroom-01", "classroom", "a classroom", [700, 600],
     [("whiteboard", 1), ("teacher desk", 1), ("office chair", 1), ("student desk", 12), ("student chair", 12)]),
    ("classroom-02", "classroom", "a classroom with student desks in rows facing the board", [800, 650],
     [("whiteboard", 1), ("teacher desk", 1), ("office chair", 1), ("student desk", 16), ("student chair", 16), ("bookshelf", 2), ("trash can", 1)]),
    ("classroom-03", "classroom", "a small seminar classroom", [550, 450],
     [("whiteboard", 1), ("teacher desk", 1), ("office chair", 1), ("student desk", 8), ("student chair", 8), ("potted plant", 1)]),
    ("classroom-04", "classroom", "a primary school classroom with lockers, a reading corner and a projector", [900, 700],
     [("whiteboard", 1), ("teacher desk", 1), ("office chair", 1), ("student desk", 12), ("student chair", 12), ("locker", 3),
      ("bookshelf", 2), ("area rug", 1), ("projector cart", 1), ("potted plant", 1)]),
    ("classroom-05", "classroom", "a classroom for eighteen students", [850, 700],
     [("whiteboard", 1), ("teacher desk", 1), ("office chair", 1), ("student desk", 18), ("student chair", 18), ("filing cabinet", 1)]),
    # children's rooms
    ("childrens-room-01", "children's room", "a children's room", [350, 320],
     [("kids bed", 1), ("toy chest", 1), ("bookshelf", 1), ("play mat", 1)]),
    ("childrens-room-02", "children's room", "a playful kids room with a play table and two small chairs", [400, 360],
     [("kids bed", 1), ("nightstand", 1), ("play table", 1), ("kids chair", 2), ("toy chest", 1), ("bookshelf", 1), ("wardrobe", 1), ("play mat", 1)]),
    ("childrens-room-03", "children's room", "a shared room for two siblings with a bunk bed and a study desk", [420, 380],
     [("bunk bed", 1), ("study desk", 1), ("office chair", 1), ("wardrobe", 1), ("toy chest", 1), ("bookshelf", 1), ("teepee tent", 1), ("rug", 1)]),
    ("childrens-room-04", "children's room", "a nursery with a crib, a rocking chair and a dresser", [360, 330],
     [("crib", 1), ("armchair", 1), ("chest of drawers", 1), ("toy chest", 1), ("floor lamp", 1), ("rocking horse", 1), ("play mat", 1)]),
    ("childrens-room-05", "children's room", "a big children's room with two beds, a play area and storage", [500, 450],
     [("single bed", 2), ("nightstand", 2), ("wardrobe", 2), ("play table", 1), ("kids chair", 3), ("toy chest", 2), ("bookshelf", 2),
      ("teepee tent", 1), ("play mat", 1), ("study desk", 1), ("office chair", 1)]),
    # home gyms
    ("home-gym-01", "home gym", "a home gym", [450, 400],
     [("treadmill", 1), ("weight bench", 1), ("dumbbell rack", 1), ("yoga mat", 1)]),
    ("home-gym-02", "home gym", "a home gym with cardio machines along one wall and a mirror", [550, 450],
     [("treadmill", 1), ("exercise bike", 1), ("elliptical", 1), ("wall mirror", 1), ("weight bench", 1), ("dumbbell rack", 1), ("fan", 1), ("gym mat", 1)]),
    ("home-gym-03", "home gym", "a garage gym with a squat rack in the center", [600, 550],
     [("squat rack", 1), ("weight bench", 1), ("dumbbell rack", 1), ("rowing machine", 1), ("punching bag", 1), ("storage cabinet", 1), ("gym mat", 1)]),
    ("home-gym-04", "home gym", "a small yoga and cardio room", [400, 350],
     [("exercise bike", 1), ("yoga mat", 2), ("wall mirror", 1), ("potted plant", 1), ("storage cabinet", 1)]),
    ("home-gym-05", "home gym", "a complete home gym", [700, 550],
     [("treadmill", 2), ("exercise bike", 1), ("rowing machine", 1), ("elliptical", 1), ("squat rack", 1), ("weight bench", 2),
      ("dumbbell rack", 2), ("wall mirror", 2), ("punching bag", 1), ("fan", 1), ("storage cabinet", 1), ("gym mat", 1)]),
]

# Room types the rules were not written for, with categories outside the knowledge file.
UNSEEN = [
    ("office-01", "office", "an open office with a meeting table", [800, 600],
     [("desk", 6), ("office chair", 6), ("meeting table", 1), ("conference chair", 8), ("filing cabinet", 2),
      ("printer stand", 1), ("water cooler", 1), ("potted plant", 2)]),
    ("library-01", "library", "a small library with bookcases along the walls and reading tables", [800, 600],
     [("bookcase", 8), ("reading table", 2), ("dining chair", 8), ("reading chair", 2), ("librarian desk", 1), ("office chair", 1),
      ("card catalogue", 1), ("globe stand", 1), ("area rug", 1)]),
    ("laundry-01", "laundry room", "a laundry room", [350, 280],
     [("washer", 1), ("dryer", 1), ("utility sink", 1), ("ironing board", 1), ("folding table", 1), ("drying rack", 1),
      ("laundry basket", 2), ("shelving unit", 1)]),
]


def scene(sid, room_type, prompt, room, items):
    assets = []
    for cat, count in items:
        for i in range(count):
            assets.append({"name": f"{cat}-{i}", "category": cat, "size": CATALOGUE[cat]})
    return {"id": sid, "prompt": prompt, "room_type": room_type,
            "room": {"width": room[0], "depth": room[1]}, "assets": assets}


def write(directory, scenes):
    os.makedirs(directory, exist_ok=True)
    for s in scenes:
        with open(os.path.join(directory, s[0] + ".json"), "w", encoding="utf-8") as f:
            json.dump(scene(*s), f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    write("bench/scenes", SCENES)
    write("bench/unseen", UNSEEN)
    print(f"wrote {len(SCENES)} scenes to bench/scenes and {len(UNSEEN)} to bench/unseen")
