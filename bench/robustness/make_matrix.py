#!/usr/bin/env python3
"""Writes bench/robustness/scenes.txt: the condition matrix of docs/robustness.md.

Deterministic (random.Random(2026)); rerun only to change the matrix, and say so in the commit.
Each line: id|split|family|mode|r_over_s|noise|colour|units|pc_synth arguments
split: 'tune' scenes may be looked at while a method is chosen; 'held-out' scenes are scored only
at the end (every scene of the grape family, of yellow fruit and of scan stripes, and one in five
of the rest); 'held-out-2' (241-340) was drawn after 'held-out' had been scored once, and
'held-out-3' (341-440) after 'held-out-2' had been, 'held-out-4' (441-540) to 'held-out-10'
(1041-1140) each after the one before; 'shapes' (1141-1240, a tune part) and 'held-out-11'
(1241-1340) have fruit of each family's shape (spheroids, SHAPE_PARTS below), as have
'held-out-12' (1341-1440), drawn after held-out-11 had been scored, 'held-out-13'
(1441-1540), drawn after held-out-12 had been, 'held-out-14' (1541-1640), after held-out-13, and
'held-out-15' (1641-1740), after held-out-14, and 'held-out-16' (1741-1840), after held-out-15."""
import random
import os

FAMILIES = {  # layout: radius (m), pc_synth flags
    'peach': (0.035, '--species peach --fruit-count 60 --canopy 0.7,0.7,0.55'),
    'apple': (0.035, '--species apple --fruit-count 80 --canopy 0.8,0.8,0.65'),
    'plum': (0.017, '--species plum --fruit-count 150 --canopy 0.6,0.6,0.5'),
    'cherry': (0.012, '--species plum --fruit-radius 0.012 --bunch-min 2 --bunch-max 6 '
                      '--touch-gap 0.001 --overlap 0.1 --fruit-count 150 --canopy 0.5,0.5,0.4'),
    'grape': (0.009, '--species plum --fruit-radius 0.009 --bunch-min 6 --bunch-max 12 '
                     '--touch-gap 0.0005 --overlap 0.05 --fruit-count 200 --canopy 0.5,0.5,0.4'),
}
MODES = ['explicit', 'implicit', 'degraded', 'surface', 'sfm', 'stripes', 'volume']
SOLID = {'explicit', 'degraded', 'volume'}       # points fill the fruit: radius <= 8 spacings
R_OVER_S = [2, 3, 5, 8, 12, 20]
NOISE = [0, 0.03, 0.1]                           # sigma / radius, sampled modes
COLOR_NOISE = [0, 12, 25]                        # sigma, 0..255 levels (held-out-25 on)
COLOURS = {'mask': None, 'red': (190, 35, 40), 'purple': (75, 30, 65), 'orange': (235, 140, 45),
           'yellow': (225, 200, 70), 'green': (125, 175, 60)}
UNITS = {'m': '', 'mm': '--scale 1000', 'normalised': '--scale 0.45 --offset 0.1,-0.05,0.2'}

SAMPLED = ('surface', 'sfm', 'stripes', 'volume')


# Wood (session 30): bark colours of real trees (apple and pear grey-brown, walnut and plum
# brown, cherry red-brown, wet or shaded bark near black); trunks 3-8 cm in radius.
BARK = {'grey-brown': (110, 100, 90), 'brown': (100, 75, 50), 'red-brown': (120, 65, 55),
        'dark-bark': (60, 50, 45)}


DENSE_R_OVER_S = [30, 45]                        # sampled modes, held-out-26 on ...
DENSE_SPACING = 0.0008                           # ... down to a spacing of 0.8 mm (camera-bound)
MIN_SPACING = 0.0004                             # every draw, held-out-48 on (see draw: floor)


def draw(rng, families, colours, ids, part, wood=False, color_noise=False, dense=False,
         barks=BARK, featured=None, leafy=False, floor=False):
    """One line per id; part(family, colour, mode) names its split (it may draw from rng).
    wood: each scene gets a tree of 3-8 main branches (drawn after everything else, so that the
    parts without wood keep their scenes); lattice modes export a fifth of the branches (fruit
    masks leak some wood, as they leak leaves), sampled modes all of them; the bark colour one of
    `barks`.
    color_noise: each scene's natural colours get N(0, sigma) per channel, sigma 0, 12 or 25
    (drawn last: SfM and NeRF colours are blended from the views that saw a point).
    dense: half the surface, SfM and stripes scenes are drawn at 30 or 45 spacings a radius
    where the spacing stays >= 0.8 mm (real SfM exports of apples sit near 75 at 0.46 mm; the
    spacing is set by the cameras, not by the fruit); drawn from the scene's own seed, so the
    other draws keep their order.
    featured: (families, colours) new in this part, each drawn for a quarter of its scenes (drawn
    uniformly, a new family of 40 came up in 2 of 100 scenes, a new colour in none).
    leafy: a quarter of the scenes export 40 % of the leaves, not 10 % (a loosely masked or
    whole-canopy export: leaf points outnumber the fruit's); drawn from the scene's own seed.
    floor: the spacings a radius drawn keep the spacing >= MIN_SPACING (0.4 mm: a whole tree is
    not sampled finer than the best real exports, SfM apples at 0.46 mm; 5 mm fruit at 20
    spacings a radius put 12-30M points on a tree of 1.6 m, 0.25 mm apart)."""
    for i in ids:
        if featured and rng.random() < 0.25:
            family = rng.choice(sorted(featured[0]))
        else:
            family = rng.choice(list(families))
        mode = rng.choice(MODES)
        rs = rng.choice([x for x in R_OVER_S if x <= (8 if mode in SOLID else 12 if mode == 'implicit' else 20)
                         and (not floor or families[family][0] / x >= MIN_SPACING)])
        noise = rng.choice(NOISE) if mode in SAMPLED else 0
        if featured and rng.random() < 0.25:
            colour = rng.choice(sorted(featured[1]))
        else:
            colour = rng.choice(list(colours))
        shading = rng.choice([0, 0.6])
        units = rng.choice(list(UNITS))
        seed = rng.randrange(1, 10**6)
        radius, flags = families[family]
        dense_rs = [x for x in DENSE_R_OVER_S if radius / x >= DENSE_SPACING]
        if dense and mode in SAMPLED and mode != 'volume' and dense_rs:
            own = random.Random(seed)
            if own.random() < 0.5:
                rs = own.choice(dense_rs)
        args = f'{flags} --radius-spread 0.2 --mode {mode} --voxel {radius / rs:.6g} --seed {seed}'
        if noise:
            args += f' --noise {noise}'
        if colour == 'mask':
            args += ' --colors mask'
        elif isinstance(colours[colour][0], tuple):  # bicoloured: ground colour, blush
            ground, blush, *share = colours[colour]
            lo, hi = share[0] if share else (0.2, 0.8)
            args += (' --fruit-rgb ' + ','.join(map(str, ground)) + ' --blush-rgb ' +
                     ','.join(map(str, blush)) + f' --blush-min {lo:g} --blush-max {hi:g}')
            if mode in SAMPLED:
                args += f' --shading {shading}'
        else:
            args += ' --fruit-rgb ' + ','.join(map(str, colours[colour]))
            if mode in SAMPLED:
                args += f' --shading {shading}'
        if UNITS[units]:
            args += ' ' + UNITS[units]
        if wood:
            bark = rng.choice(list(barks))
            args += (f' --branches {rng.randint(3, 8)} --trunk-radius {rng.uniform(0.03, 0.08):.3f}'
                     f' --wood-rgb {",".join(map(str, barks[bark]))}')
            if mode not in SAMPLED:
                args += ' --wood-leak 0.2'
        if color_noise:
            sigma = rng.choice(COLOR_NOISE)
            if sigma and colour != 'mask':
                args += f' --color-noise {sigma}'
        if leafy and random.Random(seed * 2 + 1).random() < 0.25:
            args += ' --leaf-leak 0.4'
        yield f'{i:03d}|{part(family, colour, mode)}|{family}|{mode}|{rs}|{noise}|{colour}|{units}|{args}'


rng = random.Random(2026)
lines = list(draw(rng, FAMILIES, COLOURS, range(1, 241),
                  lambda family, colour, mode: 'held-out' if (
                      family == 'grape' or colour == 'yellow' or mode == 'stripes' or rng.random() < 0.2)
                  else 'tune'))

# The later held-out parts, each drawn after the one before had been scored: new seeds, and a
# family and a colour no method had seen (added to those of the parts before). Each part's
# history (scored when, looked at since) is the table of parts in docs/robustness.md.
LATER_PARTS = [
    # part, seed, family, (radius m, pc_synth flags), colour, rgb
    # 2 (session 18): tomato-like trusses, 25 mm, bunches of 3-6 touching; brown-red fruit
    ('held-out-2', 2027, 'truss', (0.025, '--species plum --fruit-radius 0.025 --bunch-min 3 '
     '--bunch-max 6 --touch-gap 0.002 --overlap 0.05 --fruit-count 80 --canopy 0.6,0.6,0.5'),
     'brown', (140, 70, 40)),
    # 3 (session 19): citrus-like, 45 mm, single or in touching pairs; dark red, value 0.39
    ('held-out-3', 2028, 'citrus', (0.045, '--species apple --fruit-radius 0.045 --bunch-min 1 '
     '--bunch-max 2 --touch-gap 0.003 --fruit-count 50 --canopy 0.9,0.9,0.7'),
     'dark-red', (100, 20, 25)),
    # 4 (session 19): crab-apple-like, 15 mm, bunches of 2-5 touching; pink fruit
    ('held-out-4', 2029, 'crab', (0.015, '--species plum --fruit-radius 0.015 --bunch-min 2 '
     '--bunch-max 5 --touch-gap 0.001 --fruit-count 120 --canopy 0.6,0.6,0.5'),
     'pink', (235, 130, 160)),
    # 5 (session 19): olive-like, 8 mm, bunches of 3-8 touching; pale fruit
    ('held-out-5', 2030, 'olive', (0.008, '--species plum --fruit-radius 0.008 --bunch-min 3 '
     '--bunch-max 8 --touch-gap 0.0005 --fruit-count 200 --canopy 0.5,0.5,0.4'),
     'pale', (225, 215, 170)),
    # 6 (session 21): kiwi-like, 28 mm, rows of 1-4 touching, up to 5 % interpenetrating; dark
    # blue fruit
    ('held-out-6', 2031, 'kiwi', (0.028, '--species apple --fruit-radius 0.028 --bunch-min 1 '
     '--bunch-max 4 --touch-gap 0.001 --overlap 0.05 --fruit-count 90 --canopy 0.7,0.7,0.5'),
     'dark-blue', (45, 50, 120)),
    # 7 (session 22): apricot-like, 22 mm, single or in pairs 0-4 mm apart; yellow-green fruit
    # (hue about 68 degrees: at the edge of foliage green, as golden apples and pears are)
    ('held-out-7', 2032, 'apricot', (0.022, '--species apple --fruit-radius 0.022 --bunch-min 1 '
     '--bunch-max 2 --touch-gap 0.004 --fruit-count 100 --canopy 0.7,0.7,0.55'),
     'yellow-green', (175, 190, 60)),
    # 8 (session 24): fig-like, 30 mm, single or in bunches of up to 3, interpenetrating by up
    # to 10 % of the radius (the limit); violet fruit
    ('held-out-8', 2033, 'fig', (0.030, '--species apple --fruit-radius 0.03 --bunch-min 1 '
     '--bunch-max 3 --touch-gap 0.001 --overlap 0.1 --fruit-count 70 --canopy 0.7,0.7,0.55'),
     'violet', (120, 70, 140)),
    # 9 (session 25): lychee-like, 16 mm, bunches of 4-12 touching, up to 5 % interpenetrating
    # (the largest bunches); near-black red fruit (value 0.22: dark cherries, black grapes)
    ('held-out-9', 2034, 'lychee', (0.016, '--species plum --fruit-radius 0.016 --bunch-min 4 '
     '--bunch-max 12 --touch-gap 0.001 --overlap 0.05 --fruit-count 150 --canopy 0.6,0.6,0.5'),
     'black-red', (55, 15, 25)),
    # 10 (session 25): blueberry-like, 7 mm, clusters of 4-10 touching; grey-blue fruit (the
    # waxy bloom of blueberries and plums: saturation 0.3)
    ('held-out-10', 2035, 'blueberry', (0.007, '--species plum --fruit-radius 0.007 --bunch-min 4 '
     '--bunch-max 10 --touch-gap 0.0005 --fruit-count 200 --canopy 0.5,0.5,0.4'),
     'grey-blue', (105, 115, 150)),
]
families, colours, first = dict(FAMILIES), dict(COLOURS), 241
for part, seed, family, spec, colour, rgb in LATER_PARTS:
    families[family] = spec
    colours[colour] = rgb
    lines += draw(random.Random(seed), families, colours, range(first, first + 100),
                  lambda family, colour, mode, part=part: part)
    first += 100

# Fruit shapes (session 26): every scene above has spherical fruit. Real fruit are spheroids of
# their own aspect (polar / equatorial half axis; ratios of length to diameter from pomology):
# tomatoes and blueberries 0.8, apples 0.85-0.9, citrus 0.93, cherries 0.95, peaches 1.0,
# lychees 1.05, plums and apricots 1.1, figs 1.2, grapes 1.25 (oval kinds to 2), kiwis and
# olives 1.35, lemons 1.35, pears and mangos 1.5-1.6, dates 1.7-1.8; each fruit's aspect within
# ±10 % of its kind's, its axis in any direction. 'shapes' (1141-1240) is a tune part: the
# families seen so far at their aspects plus two elongated ones (pear-like 32 mm, lemon-like
# 30 mm); 'held-out-11' (1241-1340) adds date-like fruit (11 mm, aspect 1.75, bunches of 3-8
# touching) and amber fruit, scored once when the method for shapes is final.
ASPECTS = {'peach': 1.0, 'apple': 0.88, 'plum': 1.12, 'cherry': 0.95, 'grape': 1.25, 'truss': 0.8,
           'citrus': 0.93, 'crab': 0.9, 'olive': 1.35, 'kiwi': 1.35, 'apricot': 1.1, 'fig': 1.2,
           'lychee': 1.05, 'blueberry': 0.8, 'pear': 1.55, 'lemon': 1.35, 'date': 1.75,
           'mango': 1.5, 'avocado': 1.4, 'persimmon': 0.8, 'walnut': 1.1,
           'gooseberry': 1.15}
SHAPE_PARTS = [
    # part, seed, new families, new colours, families and colours left out (not yet scored)
    ('shapes', 2036,
     {'pear': (0.032, '--species apple --fruit-radius 0.032 --bunch-min 1 --bunch-max 2 '
                      '--touch-gap 0.003 --fruit-count 70 --canopy 0.7,0.7,0.55'),
      'lemon': (0.030, '--species apple --fruit-radius 0.03 --bunch-min 1 --bunch-max 3 '
                       '--touch-gap 0.002 --fruit-count 70 --canopy 0.7,0.7,0.55')},
     {}, {'blueberry', 'grey-blue'}),
    ('held-out-11', 2037,
     {'date': (0.011, '--species plum --fruit-radius 0.011 --bunch-min 3 --bunch-max 8 '
                      '--touch-gap 0.0005 --fruit-count 150 --canopy 0.5,0.5,0.4')},
     {'amber': (200, 130, 30)}, set()),
    # 12 (session 26, after held-out-10 and -11 were scored): mango-like, 45 mm, aspect 1.5,
    # single or in touching pairs; lime fruit (hue 80 degrees: inside the foliage-green band,
    # as limes and green apples are)
    ('held-out-12', 2038,
     {'mango': (0.045, '--species apple --fruit-radius 0.045 --bunch-min 1 --bunch-max 2 '
                       '--touch-gap 0.002 --fruit-count 50 --canopy 0.9,0.9,0.7')},
     {'lime': (140, 190, 40)}, set()),
    # 13 (session 27, after held-out-12 had been scored): avocado-like, 39 mm, aspect 1.4, single
    # or in touching pairs; near-black green fruit (hue 95 degrees, value 0.25: inside the
    # foliage band and dark, as ripe Hass avocados and dark green olives are)
    ('held-out-13', 2039,
     {'avocado': (0.039, '--species apple --fruit-radius 0.039 --bunch-min 1 --bunch-max 2 '
                         '--touch-gap 0.002 --fruit-count 50 --canopy 0.9,0.9,0.7')},
     {'black-green': (50, 65, 35)}, set()),
    # 14 (session 28, after held-out-13 had been scored): persimmon-like, 35 mm, oblate (aspect
    # 0.8), single or up to three touching; salmon fruit (hue 15 degrees, saturation 0.5: paler
    # than any red or orange so far, as blushed peaches and persimmons are)
    ('held-out-14', 2040,
     {'persimmon': (0.035, '--species apple --fruit-radius 0.035 --bunch-min 1 --bunch-max 3 '
                           '--touch-gap 0.002 --fruit-count 60 --canopy 0.8,0.8,0.65')},
     {'salmon': (235, 150, 120)}, set()),
    # 15 (session 29, after held-out-14 had been scored): walnut-like, 20 mm green husks, aspect
    # 1.1, single or up to three touching; olive-green fruit (hue 88 degrees, value 0.47: as dark
    # as the leaves, a little yellower, as walnut husks, green figs and unripe fruit are)
    ('held-out-15', 2041,
     {'walnut': (0.020, '--species apple --fruit-radius 0.02 --bunch-min 1 --bunch-max 3 '
                        '--touch-gap 0.002 --fruit-count 100 --canopy 0.7,0.7,0.55')},
     {'olive-green': (90, 120, 55)}, set()),
    # 16 (session 29, after held-out-15 had been scored): gooseberry-like, 9 mm, aspect 1.15, in
    # clusters of 2-6; translucent yellow-green fruit (hue 68 degrees, saturation 0.38: at the
    # edge of foliage hue and paler than the other greens)
    ('held-out-16', 2042,
     {'gooseberry': (0.009, '--species plum --fruit-radius 0.009 --bunch-min 2 --bunch-max 6 '
                            '--touch-gap 0.0005 --fruit-count 150 --canopy 0.5,0.5,0.4')},
     {'pale-green': (200, 210, 130)}, set()),
]
# Wood (session 30, written before any method saw it): every scene so far had fruit, leaves,
# ground and outliers, no trunk or branches; a natural-colour export of a whole tree has them.
# 'wood' (1841-1940) is a tune part: the families and colours seen so far with a tree of bark
# (BARK above); 'held-out-17' (1941-2040) adds quince-like fruit (38 mm, aspect 1.2, single or in
# pairs) of russet (a bark-like brown, lighter: russet pears and apples), scored once when the
# method for wood is final (session 31). 'held-out-18' (2041-2140, session 31, before any method
# for it) adds pomegranate-like fruit (45 mm, oblate aspect 0.9, single or in pairs) and a light
# apple green (140,185,80: hue 86, in the leaves' band, lighter than them), beside bark: the
# condition the wood method left (green fruit beside bark); score it once, at its end (scored in
# session 32). 'held-out-19' (2141-2240, session 32, before any method for it) adds loquat-like
# fruit (20 mm, aspect 1.3, in bunches of 3-8 touching: locally near-cylindrical, as the branch
# test of session 32 reads branches) of ochre (185,135,45: a yellow-brown near the bark's hues)
# (scored in session 33). 'held-out-20' (2241-2340, session 33, before any method for it) adds
# jujube-like fruit (13 mm, aspect 1.3, single or up to three) of mahogany (110,45,30: a dark
# red-brown, between red fruit and the red-brown bark, where shading darkens both alike)
# (scored in session 34). 'held-out-21' (2341-2440, session 34, before any method for it) adds
# hazelnut-like fruit (10 mm, aspect 1.15, in bunches of 2-4 touching) of tan (180,145,100: a
# light brown of low saturation, between the grey-brown and the brown bark in hue, lighter)
# (scored in session 34). 'held-out-22' (2441-2540, session 34, before any method for it) adds
# currant-like fruit (5 mm, round, in bunches of 6-12 touching: the size of the finest twigs) of
# cream (235,225,195: saturation 0.17, near the grey of a mask export, as white currants,
# snowberries and pale grapes are) (scored in session 35). 'held-out-23' (2541-2640, session 35,
# before any method for it) adds medlar-like fruit (25 mm, oblate aspect 0.85, single or up to
# three touching) of lavender (175,150,200: a pale violet of saturation 0.25, bluer than any
# fruit so far, as some plums and grapes with bloom are). 'held-out-24' (2641-2740, session 36,
# before any method for it) adds grapefruit-like fruit (55 mm, aspect 0.95, single or up to three
# touching: larger than any so far) and bicoloured fruit (pc_synth --blush-*: a red blush over
# 20-80 % of each fruit, on a side of its own, over a yellow (205,195,95) or a yellow-green
# (150,185,75: inside the leaves' hue band) ground colour, as Gala and Fuji apples are).
# 'held-out-25' (2741-2840, session 37, after held-out-24 was scored, before any method for it)
# adds kumquat-like fruit (14 mm, aspect 1.25, single or up to four touching) of tangerine
# (245,105,25: a deep orange between the orange and the red fruit), and colour noise: each
# scene's natural colours get N(0, sigma) per channel, sigma 0, 12 or 25 (pc_synth
# --color-noise; SfM and NeRF colours are blended from the views that saw a point).
# 'held-out-26' (2841-2940, session 38, after held-out-25 was scored, before any method for it)
# adds passion-fruit-like fruit (38 mm, aspect 1.15, single or in pairs) of a dusky purple-brown
# (95,45,55: between the purple fruit and the red-brown and near-black bark), keeps the colour
# noise, and draws dense clouds: surface, SfM and stripes scenes may be drawn at 30 or 45
# spacings a radius (the matrix topped at 20; real SfM exports sit near 75).
# 'held-out-27' (2941-3040, session 40, after held-out-26 was scored, before any method for it)
# adds pomelo-like fruit (70 mm, oblate aspect 0.9, single, 30 on a tree of 1.2 m: fruit as
# thick as the trunk or thicker, few of them) and fruit ripening unevenly (a red blush over 0 to
# 100 % of each fruit over a yellow-green ground (160,185,70): in one tree fruit wholly green,
# wholly red and between, as orchards are before harvest); colour noise and dense clouds kept.
# 'held-out-28' (3041-3140, session 40, after held-out-27 was scored, before any method for it)
# adds a fruit wall (apple-like 38 mm, aspect 0.9, single or up to three, 90 fruit in a canopy
# 1.2 m wide, 0.15 m deep and 0.9 m high: the trained planar canopies of modern orchards, the
# layout most orchard SfM and LiDAR scans are made of) and chartreuse fruit (185,205,45: hue 68,
# saturation 0.78, bright, at the yellow edge of the leaves' band, as some pears and greengages
# are); colour noise and dense clouds kept.
# 'held-out-29' (3141-3240, session 41, after held-out-28 was scored, before any method for it)
# adds chili-like fruit (12 mm, aspect 2.0: longer than any so far, in bunches of 2-4 touching),
# coral fruit (240,110,90: a pale red-orange, saturation 0.63, bright) and silver bark (birch-
# or cherry-like light grey, (175,170,160): pale, as the pale fruit are, not dark as the other
# barks; one of the five bark colours of this part only); colour noise and dense clouds kept.
# 'held-out-30' (3241-3340, session 42, after held-out-29 was scored, before any method for it)
# adds cacao-like pods (45 mm, aspect 2.2: the longest fruit so far and among the largest,
# single, 30 on a tree of 1 m) of magenta (200,40,130: hue 326, deep and saturated, between the
# purple and the pink fruit, as dragon fruit and some cacao pods are); the silver bark stays
# among the five; colour noise and dense clouds kept.
# 'held-out-31' (3341-3440, session 43, before held-out-30 was scored and any method for either)
# adds feijoa-like fruit (22 mm, aspect 1.4, single or in pairs, 70 on a tree of 0.7 m) of teal
# (70,140,130: hue 171, just past the leaves' band at its blue-green edge, as every green so far
# sat at its yellow edge or inside it; unripe blueberries and juniper berries are such); the
# silver bark stays among the five; colour noise and dense clouds kept.
# 'held-out-32' (3441-3540, session 45, before held-out-31 was scored and any method for it)
# adds saturn-peach-like fruit (30 mm, oblate aspect 0.55: the flattest so far, whose normals meet
# on a ring, not at a point; single or in pairs, 60 on a tree of 0.8 m) of kiwi brown
# (130,100,65: the colour of the bark's browns, a dE of about 12 from brown bark; kiwifruit,
# sapodilla and russet pears are such), each in a quarter of the part's scenes (FEATURED_PARTS);
# the silver bark stays among the five; colour noise and dense clouds kept.
# 'held-out-33' (3541-3640, session 46, after held-out-32 was scored, before any method for it)
# adds mulberry-like fruit (9 mm, aspect 1.6, in bunches of 2-5 touching: small, elongated and
# crowded, as mulberries and elderberry clusters are; 160 on a tree of 0.6 m) of ivory
# (245,240,225: saturation 0.08, value 0.96, the nearest to white of any natural colour so far:
# white currants, snowberries; a natural cloud whose fruit look like a mask export's white),
# each in a quarter of the part's scenes (FEATURED_PARTS); the silver bark stays among the
# five; colour noise and dense clouds kept.
# 'held-out-34' (3641-3740, session 47, after held-out-33 was scored, before any method for it)
# adds jackfruit-like fruit (150 mm, aspect 1.5, single or in pairs, 12 on a tree of 2 m: the
# largest fruit so far by twice, few on a large tree, as jackfruit, melons on a trellis and
# pumpkins are) of bloom blue (110,125,160: saturation 0.31, just over the saturation line, hue
# 222: the dusty blue of blueberries and sloes under their bloom), each in a quarter of the
# part's scenes (FEATURED_PARTS); the silver bark stays among the five; colour noise and dense
# clouds kept.
# 'held-out-35' (3741-3840, session 47, after held-out-34 was scored, before any method for it)
# adds banana-like fruit (18 mm, aspect 2.8: the longest so far, in hands of 6-12 touching, 120 on
# a tree of 0.8 m) of pale pink (250,215,220: saturation 0.14, under the saturation line, of a
# red hue: pink-blushed pears, pitaya flesh, pale lychees), each in a quarter of the part's
# scenes (FEATURED_PARTS); the silver bark stays among the five; colour noise and dense clouds
# kept.
# 'held-out-36' (3841-3940, session 48, after held-out-35 was scored, before any method for it)
# adds coconut-like fruit (100 mm, aspect 1.2, in bunches of 4-10 touching, 40 on a tree of
# 2 m: large fruit crowded, where every bunch so far was of small fruit) of mint (215,230,200:
# saturation 0.13, under the saturation line, of a green hue inside the leaves' band: young
# coconuts, honeydew melons, pale gooseberries), each in a quarter of the part's scenes
# (FEATURED_PARTS); the silver bark stays among the five; colour noise and dense clouds kept.
# 'held-out-37' (3941-4040, session 49, after held-out-36 was scored, before any method for it)
# adds eggplant-like fruit (40 mm, aspect 2.5, single or in pairs, 30 on a plant of 1.2 m: long
# fruit hanging alone, where the only long ones so far were crowded in hands) of black (40,30,35:
# value 0.16, saturation 0.25, under the saturation line: blackberries, black olives,
# blackcurrants, the darkest fruit so far, darker than the near-black bark), each in a quarter
# of the part's scenes (FEATURED_PARTS); the silver bark stays among the five; colour noise and
# dense clouds kept.
# 'held-out-38' (4041-4140, session 51, after held-out-37 was scored, before any method for it)
# adds strawberry-like fruit (12 mm, aspect 1.25, single or in threes, 120 on a low bed of
# 1.6 x 0.6 x 0.3 m: fruit in a flat layer near the ground, as strawberries, tomatoes on the
# ground and melons lie) of jade (80,150,110: hue 146, on the blue side of the leaves' green
# (hue 109), where every green fruit so far sat on the yellow side, and teal beyond it at 171),
# each in a quarter of the part's scenes (FEATURED_PARTS); and leafy exports (a quarter of the
# scenes export 40 % of the leaves, not 10 %: LEAFY_PARTS); the silver bark stays among the
# five; colour noise and dense clouds kept.
# 'held-out-39' (4141-4240, session 51, after held-out-38 was scored, before any method for it)
# adds lime-like fruit (25 mm, aspect 1.1, single or in pairs, 100 anywhere in a canopy of 1.6 m,
# not only in its outer half (--shell 0): fruit deep among the leaves and branches, as citrus
# hang) of indigo (70,55,140: hue 251, between the dark blue (236) and the violet (283) fruit
# so far, saturated: damsons, indigo berries), each in a quarter of the part's scenes; leafy
# exports, silver bark, colour noise and dense clouds kept.
# 'held-out-40' (4241-4340, session 52, after held-out-39 was scored, before any method for it)
# adds cucumber-like fruit (20 mm for a sphere of the same volume, aspect 3.5: longer than the
# bananas, hanging single or in pairs, 60 in a canopy of 1.6 m, as greenhouse cucumbers and
# long peppers hang) of rose (215,90,130: hue 334, between the magenta (325) and the coral (7)
# fruit so far), each in a quarter of the part's scenes; leafy exports, silver bark, colour
# noise and dense clouds kept.
# 'held-out-41' (4341-4440, session 53, after held-out-40 was scored, before any method for it)
# adds avocado-like fruit (40 mm, aspect 1.4, single, only 15 in a canopy of 1.6 m: few large
# fruit among many leaves and branches, where the median cluster is a leaf's or a branch's) of
# khaki (140,130,60: hue 53, a dull yellow just outside the foliage band's yellow edge, value
# 0.55: russet pears, olive-drab figs), each in a quarter of the part's scenes; leafy exports,
# silver bark, colour noise and dense clouds kept.
# 'held-out-42' (4441-4540, session 54, after held-out-41 was scored, before any method for it)
# adds nectarine-like fruit (32 mm, round, single or in pairs 0-1 mm apart, 120 on a tree of
# 2.4 m: the issue's own kind of fruit, round and smooth, on a tree half again as wide as any
# round fruit's so far) of sage (150,165,130: hue 86, saturation 0.21, a grey-green inside the
# foliage band and under the pale greens' saturation: unripe quinces, grey-green pears and
# feijoas under their bloom), each in a quarter of the part's scenes; leafy exports, silver
# bark, colour noise and dense clouds kept.
# 'held-out-43' (4541-4640, session 55, after held-out-42 was scored, before any method for it)
# adds persimmon-like fruit (35 mm, oblate, aspect 0.8, single, 50 on a tree of 1.6 m: flattened
# fruit, where the only oblate ones so far were the saturn peaches) of hass (55,70,45: hue 96,
# value 0.27, inside the foliage band and darker than the leaves: Hass avocados, dark unripe
# fruit in shade), each in a quarter of the part's scenes; leafy exports, silver bark, colour
# noise and dense clouds kept.
# 'held-out-44' (4641-4740, session 56, after held-out-43 was scored, before any method for it)
# adds caper-like fruit (9 mm, aspect 1.3, single or in pairs 2 mm apart, 250 on a tree of
# 2.4 m: many small fruit spread thin over a large tree, the fruit's radius under 0.4 % of the
# canopy's width, where the smallest fruit so far hung in bunches or on smaller plants) of
# glaucous (95,135,150: hue 196, a blue-green under a grey bloom, between the teal (171) and the
# bloom-blue (223) fruit so far: juniper berries, unripe blueberries), each in a quarter of the
# part's scenes; leafy exports, silver bark, colour noise and dense clouds kept.
# 'held-out-45' (4741-4840, session 57, after held-out-44 was scored, before any method for it)
# adds sloe-like fruit (7 mm, round, single or in pairs 1 mm apart, 300 anywhere in a dense
# shrub of 1.6 m (--shell 0): many small fruit deep among the leaves and twigs, as blackthorn
# and juniper bear them) of slate (70,75,95: hue 228, saturation 0.26, value 0.37: a dark
# blue-grey on the saturation line, under colour noise half its points pale: sloes and damsons
# under their bloom in shade), each in a quarter of the part's scenes; leafy exports, silver
# bark, colour noise and dense clouds kept.
# 'held-out-46' (4841-4940, session 58, after held-out-45 was scored, before any method for it)
# adds tamarillo-like fruit (25 mm, egg-shaped, aspect 1.5, in bunches of 2-5 touching 1 mm
# apart, 80 on a tree of 2 m: long fruit hanging side by side, where the long fruit so far hung
# alone or in hands) of taupe (150,130,115: hue 26, saturation 0.23, value 0.59: a grey-brown
# near the barks' colours: russeted and scurfy fruit, sapodillas, medlars in shade), each in a
# quarter of the part's scenes; leafy exports, silver bark, colour noise and dense clouds kept.
# 'held-out-47' (4941-5040, session 59, after held-out-46 was scored, before any method for it)
# adds longan-like fruit (11 mm, round, in bunches of 6-12 touching 0.5 mm apart, 200 on a tree
# of 2 m: large tight clusters of small round fruit, where such bunches so far were grapes and
# currants) of mauve (175,130,160: hue 320, saturation 0.26, value 0.69: a greyish pink-purple on
# the saturation line, between the pale-pink, lavender and dusky fruit so far: bloomed plums,
# ripening figs, heather-coloured berries), each in a quarter of the part's scenes; leafy
# exports, silver bark, colour noise and dense clouds kept.
# 'held-out-48' (5041-5140, session 60, after held-out-47 was scored, before any method for it)
# adds rowan-like fruit (5 mm, round, in bunches of 8-16 touching 0.3 mm apart, 240 on a shrub of
# 1 m: umbels of tiny berries, smaller and in larger bunches than any so far) of copper
# (185,95,55: hue 18, saturation 0.70, value 0.73: an orange-brown between the tangerine and
# russet fruit and the barks' hues: rowan and sea-buckthorn berries, copper beech nuts), each in
# a quarter of the part's scenes; leafy exports, silver bark, colour noise and dense clouds kept;
# from this part on no scene's spacing is under 0.4 mm (MIN_SPACING).
# 'held-out-49' (5141-5240, session 61, after held-out-48 was scored, before any method for it)
# adds acerola-like fruit (8 mm, oblate, aspect 0.85, single or up to three touching 0.5 mm apart,
# 200 on a shrub of 1.6 m: small flattened fruit, where the oblate ones so far were 25-45 mm) of
# wine (125,35,70: hue 337, saturation 0.72, value 0.49: a dark purplish red between the
# dark-red, dusky and magenta fruit: acerolas, cornelian and sour cherries in shade), each in a
# quarter of the part's scenes; leafy exports, silver bark, colour noise, dense clouds and the
# spacing floor kept.
# 'held-out-50' (5241-5340, session 62, after held-out-49 was scored, before any method for it)
# adds elderberry-like fruit (3.5 mm, round, in bunches of 10-20 touching 0.2 mm apart, 300 on a
# shrub of 1.2 m: the smallest fruit so far, in flat umbels as the rowans were) of sky
# (120,170,210: hue 207, saturation 0.43, value 0.82: a light blue, lighter and more saturated
# than the glaucous and grey-blue fruit: bloomed haskap, juniper and blue elderberries in the
# light), each in a quarter of the part's scenes; leafy exports, silver bark, colour noise, dense
# clouds and the spacing floor kept (the fruit then spans at most 8 spacings a radius).
# 'held-out-51' (5341-5440, session 63, after held-out-50 was scored, before any method for it)
# adds okra-like fruit (8 mm for a sphere of the same volume, aspect 3.6: long and thin, 10.4 mm
# thick and 38 mm long, in bunches of 3-6 touching 0.5 mm apart, 120 on a plant of 1 m: the
# long fruit so far were 12-45 mm and at most aspect 3.5) of turquoise (65,190,175: hue 173,
# saturation 0.66, value 0.75: a blue-green beyond the teal and jade fruit, as porcelain berries
# and unripe blue fruit are), each in a quarter of the part's scenes; leafy exports, silver bark,
# colour noise, dense clouds and the spacing floor kept.
# 'held-out-52' (5441-5540, session 64, after held-out-51 was scored, before any method for it)
# adds papaya-like fruit (60 mm for a sphere of the same volume, aspect 1.8, in bunches of 3-8
# touching 1 mm apart, 30 on a narrow plant of 0.4 x 0.4 x 1 m: large long fruit crowded in a
# column, where the large fruit so far hung single or in loose pairs) of gold (220,170,30: hue
# 44, saturation 0.86, value 0.86: a deep saturated yellow between the amber and yellow fruit:
# ripe papayas, quinces and yellow plums in the sun), each in a quarter of the part's scenes;
# leafy exports, silver bark, colour noise, dense clouds and the spacing floor kept.
# 'held-out-53' (5541-5640, session 65, after held-out-52 was scored, before any method for it)
# adds melon-like fruit (90 mm for a sphere of the same volume, aspect 1.15, single or in pairs
# touching 2 mm apart, 16 in a wide low layer of 2 x 2 x 0.7 m: large fruit lying apart, few
# to a scene, so one fruit is 6 % of the count; the coconut-like, 100 mm, hung crowded in
# bunches) of sand (210,185,140: hue 39, saturation 0.33, value 0.82: a pale yellow-brown near
# the saturation line and the barks' hue, as netted melons, quinces under russet and dry gourds
# are), each in a quarter of the part's scenes; leafy exports, silver bark, colour noise, dense
# clouds and the spacing floor kept.
# From held-out-29 on: the four barks and a silver one, pale as the pale fruit are.
WITH_SILVER = {**BARK, 'silver': (175, 170, 160)}
WOOD_PARTS = [
    ('wood', 2043, {}, {}, {'gooseberry', 'pale-green'}),
    ('held-out-17', 2044,
     {'quince': (0.038, '--species apple --fruit-radius 0.038 --bunch-min 1 --bunch-max 2 '
                        '--touch-gap 0.002 --fruit-count 60 --canopy 0.8,0.8,0.65')},
     {'russet': (165, 115, 65)}, set()),
    ('held-out-18', 2045,
     {'pomegranate': (0.045, '--species apple --fruit-radius 0.045 --bunch-min 1 --bunch-max 2 '
                             '--touch-gap 0.002 --fruit-count 50 --canopy 0.9,0.9,0.7')},
     {'apple-green': (140, 185, 80)}, set()),
    ('held-out-19', 2046,
     {'loquat': (0.020, '--species plum --fruit-radius 0.020 --bunch-min 3 --bunch-max 8 '
                        '--touch-gap 0.001 --overlap 0.05 --fruit-count 120 '
                        '--canopy 0.6,0.6,0.5')},
     {'ochre': (185, 135, 45)}, set()),
    ('held-out-20', 2047,
     {'jujube': (0.013, '--species plum --fruit-radius 0.013 --bunch-min 1 --bunch-max 3 '
                        '--touch-gap 0.001 --fruit-count 150 --canopy 0.5,0.5,0.4')},
     {'mahogany': (110, 45, 30)}, set()),
    ('held-out-21', 2048,
     {'hazelnut': (0.010, '--species plum --fruit-radius 0.010 --bunch-min 2 --bunch-max 4 '
                          '--touch-gap 0.0005 --fruit-count 150 --canopy 0.5,0.5,0.4')},
     {'tan': (180, 145, 100)}, set()),
    ('held-out-22', 2049,
     {'currant': (0.005, '--species plum --fruit-radius 0.005 --bunch-min 6 --bunch-max 12 '
                         '--touch-gap 0.0003 --fruit-count 200 --canopy 0.5,0.5,0.4')},
     {'cream': (235, 225, 195)}, set()),
    ('held-out-23', 2050,
     {'medlar': (0.025, '--species apple --fruit-radius 0.025 --bunch-min 1 --bunch-max 3 '
                        '--touch-gap 0.002 --fruit-count 80 --canopy 0.6,0.6,0.5')},
     {'lavender': (175, 150, 200)}, set()),
    ('held-out-24', 2051,
     {'grapefruit': (0.055, '--species apple --fruit-radius 0.055 --bunch-min 1 --bunch-max 3 '
                            '--touch-gap 0.003 --fruit-count 40 --canopy 1.0,1.0,0.8')},
     {'blush-yellow': ((205, 195, 95), (180, 40, 50)),
      'blush-green': ((150, 185, 75), (175, 45, 55))}, set()),
    ('held-out-25', 2052,
     {'kumquat': (0.014, '--species plum --fruit-radius 0.014 --bunch-min 1 --bunch-max 4 '
                         '--touch-gap 0.001 --fruit-count 120 --canopy 0.6,0.6,0.5')},
     {'tangerine': (245, 105, 25)}, set()),
    ('held-out-26', 2053,
     {'passion': (0.038, '--species apple --fruit-radius 0.038 --bunch-min 1 --bunch-max 2 '
                         '--touch-gap 0.002 --fruit-count 50 --canopy 0.8,0.8,0.65')},
     {'dusky': (95, 45, 55)}, set()),
    ('held-out-27', 2054,
     {'pomelo': (0.070, '--species apple --fruit-radius 0.07 --bunch-min 1 --bunch-max 1 '
                        '--fruit-count 30 --canopy 1.2,1.2,1.0')},
     {'ripening': ((160, 185, 70), (185, 40, 45), (0, 1))}, set()),
    ('held-out-28', 2055,
     {'wall': (0.038, '--species apple --fruit-radius 0.038 --bunch-min 1 --bunch-max 3 '
                      '--touch-gap 0.002 --fruit-count 90 --canopy 0.6,0.075,0.45')},
     {'chartreuse': (185, 205, 45)}, set()),
    ('held-out-29', 2056,
     {'chili': (0.012, '--species plum --fruit-radius 0.012 --bunch-min 2 --bunch-max 4 '
                       '--touch-gap 0.001 --fruit-count 120 --canopy 0.6,0.6,0.5')},
     {'coral': (240, 110, 90)}, set(), WITH_SILVER),
    ('held-out-30', 2057,
     {'pod': (0.045, '--species apple --fruit-radius 0.045 --bunch-min 1 --bunch-max 1 '
                     '--fruit-count 30 --canopy 1.0,1.0,0.8')},
     {'magenta': (200, 40, 130)}, set(), WITH_SILVER),
    ('held-out-31', 2058,
     {'feijoa': (0.022, '--species apple --fruit-radius 0.022 --bunch-min 1 --bunch-max 2 '
                        '--touch-gap 0.002 --fruit-count 70 --canopy 0.7,0.7,0.55')},
     {'teal': (70, 140, 130)}, set(), WITH_SILVER),
    ('held-out-32', 2059,
     {'saturn': (0.030, '--species apple --fruit-radius 0.03 --bunch-min 1 --bunch-max 2 '
                        '--touch-gap 0.002 --fruit-count 60 --canopy 0.8,0.8,0.65')},
     {'kiwi-brown': (130, 100, 65)}, set(), WITH_SILVER),
    ('held-out-33', 2060,
     {'mulberry': (0.009, '--species plum --fruit-radius 0.009 --bunch-min 2 --bunch-max 5 '
                          '--touch-gap 0.0005 --fruit-count 160 --canopy 0.6,0.6,0.5')},
     {'ivory': (245, 240, 225)}, set(), WITH_SILVER),
    ('held-out-34', 2061,
     {'jackfruit': (0.150, '--species apple --fruit-radius 0.15 --bunch-min 1 --bunch-max 2 '
                           '--touch-gap 0.005 --fruit-count 12 --canopy 2.0,2.0,1.6')},
     {'bloom-blue': (110, 125, 160)}, set(), WITH_SILVER),
    ('held-out-35', 2062,
     {'banana': (0.018, '--species apple --fruit-radius 0.018 --bunch-min 6 --bunch-max 12 '
                        '--touch-gap 0.0005 --fruit-count 120 --canopy 0.8,0.8,0.65')},
     {'pale-pink': (250, 215, 220)}, set(), WITH_SILVER),
    ('held-out-36', 2063,
     {'coconut': (0.100, '--species apple --fruit-radius 0.1 --bunch-min 4 --bunch-max 10 '
                         '--touch-gap 0.004 --fruit-count 40 --canopy 2.0,2.0,1.6')},
     {'mint': (215, 230, 200)}, set(), WITH_SILVER),
    ('held-out-37', 2064,
     {'eggplant': (0.040, '--species apple --fruit-radius 0.04 --bunch-min 1 --bunch-max 2 '
                          '--touch-gap 0.003 --fruit-count 30 --canopy 1.2,1.2,1.0')},
     {'black': (40, 30, 35)}, set(), WITH_SILVER),
    ('held-out-38', 2065,
     {'strawberry': (0.012, '--species apple --fruit-radius 0.012 --bunch-min 1 --bunch-max 3 '
                            '--touch-gap 0.002 --fruit-count 120 --canopy 0.8,0.3,0.15')},
     {'jade': (80, 150, 110)}, set(), WITH_SILVER),
    ('held-out-39', 2066,
     {'lime': (0.025, '--species apple --fruit-radius 0.025 --bunch-min 1 --bunch-max 2 '
                      '--touch-gap 0.002 --fruit-count 100 --canopy 0.8,0.8,0.65 --shell 0')},
     {'indigo': (70, 55, 140)}, set(), WITH_SILVER),
    ('held-out-40', 2067,
     {'cucumber': (0.020, '--species apple --fruit-radius 0.02 --bunch-min 1 --bunch-max 2 '
                          '--touch-gap 0.002 --fruit-count 60 --canopy 0.8,0.8,0.65')},
     {'rose': (215, 90, 130)}, set(), WITH_SILVER),
    ('held-out-41', 2068,
     {'avocado': (0.040, '--species apple --fruit-radius 0.04 --bunch-min 1 --bunch-max 1 '
                         '--fruit-count 15 --canopy 0.8,0.8,0.65')},
     {'khaki': (140, 130, 60)}, set(), WITH_SILVER),
    ('held-out-42', 2069,
     {'nectarine': (0.032, '--species apple --fruit-radius 0.032 --bunch-min 1 --bunch-max 2 '
                           '--touch-gap 0.001 --fruit-count 120 --canopy 1.2,1.2,0.9')},
     {'sage': (150, 165, 130)}, set(), WITH_SILVER),
    ('held-out-43', 2070,
     {'persimmon': (0.035, '--species apple --fruit-radius 0.035 --bunch-min 1 --bunch-max 1 '
                           '--fruit-count 50 --canopy 0.8,0.8,0.65')},
     {'hass': (55, 70, 45)}, set(), WITH_SILVER),
    ('held-out-44', 2071,
     {'caper': (0.009, '--species plum --fruit-radius 0.009 --bunch-min 1 --bunch-max 2 '
                       '--touch-gap 0.002 --fruit-count 250 --canopy 1.2,1.2,0.9')},
     {'glaucous': (95, 135, 150)}, set(), WITH_SILVER),
    ('held-out-45', 2072,
     {'sloe': (0.007, '--species plum --fruit-radius 0.007 --bunch-min 1 --bunch-max 2 '
                      '--touch-gap 0.001 --fruit-count 300 --canopy 0.8,0.8,0.7 --shell 0')},
     {'slate': (70, 75, 95)}, set(), WITH_SILVER),
    ('held-out-46', 2073,
     {'tamarillo': (0.025, '--species plum --fruit-radius 0.025 --bunch-min 2 --bunch-max 5 '
                           '--touch-gap 0.001 --fruit-count 80 --canopy 1.0,1.0,0.8')},
     {'taupe': (150, 130, 115)}, set(), WITH_SILVER),
    ('held-out-47', 2074,
     {'longan': (0.011, '--species plum --fruit-radius 0.011 --bunch-min 6 --bunch-max 12 '
                        '--touch-gap 0.0005 --fruit-count 200 --canopy 1.0,1.0,0.8')},
     {'mauve': (175, 130, 160)}, set(), WITH_SILVER),
    ('held-out-48', 2075,
     {'rowan': (0.005, '--species plum --fruit-radius 0.005 --bunch-min 8 --bunch-max 16 '
                       '--touch-gap 0.0003 --fruit-count 240 --canopy 0.5,0.5,0.4')},
     {'copper': (185, 95, 55)}, set(), WITH_SILVER),
    ('held-out-49', 2076,
     {'acerola': (0.008, '--species plum --fruit-radius 0.008 --bunch-min 1 --bunch-max 3 '
                         '--touch-gap 0.0005 --fruit-count 200 --canopy 0.8,0.8,0.7')},
     {'wine': (125, 35, 70)}, set(), WITH_SILVER),
    ('held-out-50', 2077,
     {'elderberry': (0.0035, '--species plum --fruit-radius 0.0035 --bunch-min 10 --bunch-max 20 '
                             '--touch-gap 0.0002 --fruit-count 300 --canopy 0.6,0.6,0.5')},
     {'sky': (120, 170, 210)}, set(), WITH_SILVER),
    ('held-out-51', 2078,
     {'okra': (0.008, '--species plum --fruit-radius 0.008 --bunch-min 3 --bunch-max 6 '
                      '--touch-gap 0.0005 --fruit-count 120 --canopy 0.6,0.6,0.8')},
     {'turquoise': (65, 190, 175)}, set(), WITH_SILVER),
    ('held-out-52', 2079,
     {'papaya': (0.060, '--species apple --fruit-radius 0.06 --bunch-min 3 --bunch-max 8 '
                        '--touch-gap 0.001 --fruit-count 30 --canopy 0.4,0.4,1.0')},
     {'gold': (220, 170, 30)}, set(), WITH_SILVER),
    ('held-out-53', 2080,
     {'melon': (0.090, '--species apple --fruit-radius 0.09 --bunch-min 1 --bunch-max 2 '
                       '--touch-gap 0.002 --fruit-count 16 --canopy 1.0,1.0,0.35')},
     {'sand': (210, 185, 140)}, set(), WITH_SILVER),
]


def from_part(first_part):
    """The parts of WOOD_PARTS from `first_part` on: each later part keeps the conditions
    brought in before it."""
    names = [w[0] for w in WOOD_PARTS]
    return set(names[names.index(first_part):])


COLOUR_NOISE_PARTS = from_part('held-out-25')
DENSE_PARTS = from_part('held-out-26')
FEATURED_PARTS = from_part('held-out-32')
LEAFY_PARTS = from_part('held-out-38')
FLOOR_PARTS = from_part('held-out-48')
ASPECTS['quince'] = 1.2
ASPECTS['pomegranate'] = 0.9
ASPECTS['loquat'] = 1.3
ASPECTS['jujube'] = 1.3
ASPECTS['hazelnut'] = 1.15
ASPECTS['currant'] = 1.0
ASPECTS['medlar'] = 0.85
ASPECTS['grapefruit'] = 0.95
ASPECTS['kumquat'] = 1.25
ASPECTS['passion'] = 1.15
ASPECTS['pomelo'] = 0.9
ASPECTS['wall'] = 0.9
ASPECTS['chili'] = 2.0
ASPECTS['pod'] = 2.2
ASPECTS['feijoa'] = 1.4
ASPECTS['saturn'] = 0.55
ASPECTS['mulberry'] = 1.6
ASPECTS['jackfruit'] = 1.5
ASPECTS['banana'] = 2.8
ASPECTS['coconut'] = 1.2
ASPECTS['eggplant'] = 2.5
ASPECTS['strawberry'] = 1.25
ASPECTS['lime'] = 1.1
ASPECTS['cucumber'] = 3.5
ASPECTS['avocado'] = 1.4
ASPECTS['nectarine'] = 1.0
ASPECTS['persimmon'] = 0.8
ASPECTS['caper'] = 1.3
ASPECTS['sloe'] = 1.0
ASPECTS['tamarillo'] = 1.5
ASPECTS['longan'] = 1.0
ASPECTS['rowan'] = 1.0
ASPECTS['acerola'] = 0.85
ASPECTS['elderberry'] = 1.0
ASPECTS['okra'] = 3.6
ASPECTS['papaya'] = 1.8
ASPECTS['melon'] = 1.15
for part, seed, new_families, new_colours, left_out, *barks in SHAPE_PARTS + WOOD_PARTS:
    families.update(new_families)
    colours.update(new_colours)
    shaped = {f: (r, flags + (f' --aspect {ASPECTS[f]:g} --aspect-spread 0.1' if ASPECTS[f] != 1 else ''))
              for f, (r, flags) in families.items() if f not in left_out}
    palette = {c: rgb for c, rgb in colours.items() if c not in left_out}
    lines += draw(random.Random(seed), shaped, palette, range(first, first + 100),
                  lambda family, colour, mode, part=part: part,
                  wood=part in {w[0] for w in WOOD_PARTS},
                  color_noise=part in COLOUR_NOISE_PARTS, dense=part in DENSE_PARTS,
                  barks=barks[0] if barks else BARK,
                  featured=(new_families, new_colours) if part in FEATURED_PARTS else None,
                  leafy=part in LEAFY_PARTS, floor=part in FLOOR_PARTS)
    first += 100

out = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'scenes.txt')
with open(out, 'w') as f:
    f.write('\n'.join(lines) + '\n')
counts = ', '.join(f'{sum(f"|{p}|" in l for l in lines)} in {p}' for p, *_ in LATER_PARTS + SHAPE_PARTS + WOOD_PARTS)
print(f'{out}: {len(lines)} scenes, {sum("|tune|" in l for l in lines)} tune, {counts}')
