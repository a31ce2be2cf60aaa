#!/usr/bin/env python3
"""Writes data/scenarios/calot-*.toml from data/scenarios/cholecystectomy.toml (issue 36).
Each is the default with a [calot_triangle] built from the default's context tubes, the hook's
exchange, a name and description, the laparoscope aimed at the triangle (look_at_m, insertion_m),
and the context the simulated triangle replaces removed (the four ducts' and artery's tubes and
the static fat over the triangle).
Run after changing the default scenario (tests/scenario/calot_variant_scenarios_test.cpp checks
that the files differ from the default only in these):  python3 scripts/make_calot_scenarios.py ."""
import re, sys, math
root = sys.argv[1]
text = open(root + "/data/scenarios/cholecystectomy.toml").read()

def blocks(t):
    # split into the header comment and the [..] blocks (each with the comment lines just before it)
    return t

# the context tubes' points
def tube_points(name):
    m = re.search(r'\[\[context_organs\]\]\nname = "' + re.escape(name) + r'".*?\npoints_m = (\[\[.*?\]\])\n', text, re.S)
    return [tuple(float(x) for x in p.split(",")) for p in re.findall(r"\[([^\[\]]+)\]", m.group(1))]

duct = tube_points("cystic duct")          # gallbladder side first
chd = tube_points("common hepatic duct")   # hilum to the junction
cbd = tube_points("common bile duct")      # junction to the duodenum
art = tube_points("cystic artery")         # patient's side first
eye = (0.0, 0.116543, -0.10)               # the umbilical port, near the scope's tip

add = lambda a, b: tuple(x + y for x, y in zip(a, b))
sub = lambda a, b: tuple(x - y for x, y in zip(a, b))
mul = lambda s, a: tuple(s * x for x in a)
norm = lambda a: math.sqrt(sum(x * x for x in a))
unit = lambda a: mul(1.0 / norm(a), a)
lerp = lambda a, b, f: add(a, mul(f, sub(b, a)))
r4 = lambda p: tuple(round(x, 4) for x in p)

neck = duct[0]
junction = duct[-1]
assert norm(sub(junction, cbd[0])) < 1e-9 and norm(sub(junction, chd[-1])) < 1e-9

def fmt(points):
    return "[" + ", ".join("[%.4f, %.4f, %.4f]" % r4(p) for p in points) + "]"

def triangle(variant, neck, tubes, note):
    out = ["", "# Calot's triangle, simulated (issue 36; docs/calot.md, docs/calot-training.md). Each tube runs",
           "# from the patient's side (held) to the neck or its clamped far end; clips are judged against",
           "# planned_cut_s (default 0.6: two on the patient's side of it, one on the gallbladder's).",
           "# The physics replaces the static context tubes of these four structures and the static fat",
           "# over the triangle; the view draws the simulated tubes and fat layer (app/render/calot_actors.h).",
           "[calot_triangle]", 'variant = "%s"' % variant, "neck_m = [%.4f, %.4f, %.4f]" % r4(neck)]
    for name, kind, points, comment in tubes:
        out += ["", "[[calot_triangle.tubes]]", 'name = "%s"%s' % (name, ("   # " + comment) if comment else ""),
                'kind = "%s"' % kind, "points_m = " + fmt(points)]
    return "\n".join(out) + "\n"

standard_tubes = lambda d, a, h, b: [
    ("cystic duct", "cystic_duct", d, "from its junction with the common duct to the neck"),
    ("cystic artery", "cystic_artery", a, "from the right hepatic artery to the neck"),
    ("common hepatic duct", "common_hepatic_duct", h, "out of the hilum down to the junction"),
    ("common bile duct", "common_bile_duct", b, "from the junction down to the duodenum")]

variants = {}
variants["standard"] = ("standard", "the usual anatomy: a 4 cm cystic duct, the artery above it",
                        standard_tubes(list(reversed(duct)), art, chd, cbd),
                        "Clear the triangle until only the cystic duct and the cystic artery enter the gallbladder, then clip each twice on the patient's side and once on the gallbladder's and divide between.")

# Short cystic duct: the common duct swings toward the gallbladder, the junction 8 mm from the neck.
toward = unit(sub(junction, neck))
j_short = add(neck, mul(0.008, toward))
variants["short-duct"] = ("short cystic duct", "a short cystic duct (8 mm): the gallbladder's neck sits close to the common duct",
                          standard_tubes([j_short, neck], art, [chd[0], chd[1], j_short], [j_short, cbd[1], cbd[2]]),
                          "A short cystic duct: the gallbladder's neck lies 8 mm from the common duct. Clip close to the gallbladder and keep the common duct in view.")

# Low insertion: the cystic duct runs 5 mm (centre to centre: its wall against the common duct's) to the
# patient's right of the common bile duct and joins it 20 mm below the default's junction. The common
# duct keeps the default's names (the part beside the cystic duct stays "common bile duct").
low = lerp(cbd[1], cbd[2], 0.5)
beside = (-0.005, 0.0, 0.0)
variants["low-insertion"] = ("low insertion beside the common bile duct",
                             "a low-inserting cystic duct running parallel to, and touching, the common bile duct",
                             standard_tubes([low, add(cbd[1], beside), add(cbd[0], beside), neck], art, chd, cbd),
                             "A low-inserting cystic duct runs beside the common bile duct before it joins it: follow it from the gallbladder and clip it away from the common duct.")

# Artery in front: from the medial side of the common hepatic duct, 6 mm in front of it as the
# camera sees it (toward the umbilical scope: +y and -z), to the neck.
mid = chd[1]
front = unit(sub(eye, mid))
variants["anterior-artery"] = ("cystic artery crossing in front of the common hepatic duct",
                               "the cystic artery crosses in front of the common hepatic duct",
                               standard_tubes(list(reversed(duct)),
                                              [add(add(mid, (0.012, 0.0, 0.0)), mul(0.003, front)), add(mid, mul(0.006, front)), art[-1]],
                                              chd, cbd),
                               "The cystic artery crosses in front of the common hepatic duct: identify it before it reaches the gallbladder and clip it there, not on the duct behind it.")

# The camera assistant's view for this step: the scope aimed at the hepatocystic triangle and
# brought in, so that the neck, the cystic duct and artery, the common hepatic duct and the common
# bile duct's course fill the middle of the picture under the liver's edge (the default looks at
# the liver bed from farther out). The same view for every variant, so that the anatomy, not the
# camera, tells them apart: halfway between the standard triangle's centroid (neck, junction,
# hilum) and the junction, so that the common bile duct's upper course shows below the triangle,
# from about 8 cm (tests/field/calot_first_frame_test.cpp).
corners = (neck, junction, chd[0])
aim = lerp(mul(1.0 / 3.0, add(add(corners[0], corners[1]), corners[2])), junction, 0.5)
scope_insertion_m = 0.14

def aimed_at_the_triangle(t):
    t, n = re.subn(r'(\[laparoscope\]\n(?:[^\n\[][^\n]*\n)*?)look_at_m = [^\n]*\n',
                   r'\g<1>look_at_m = [%.4f, %.4f, %.4f]      # the hepatocystic triangle (scripts/make_calot_scenarios.py)\n' % r4(aim), t, count=1)
    assert n == 1
    t, n = re.subn(r'(\[laparoscope\]\n(?:[^\n\[][^\n]*\n)*?)insertion_m = [^\n]*\n',
                   r'\g<1>insertion_m = %.2f                         # in close, as for the triangle\n' % scope_insertion_m, t, count=1)
    assert n == 1
    return t

def without_context_tubes(t):
    # The static fat over the triangle: the simulated layer replaces it.
    t, n = re.subn(r'\[\[context_organs\]\]\nname = "fat over the hepatocystic triangle"[^\n]*\n(?:[^\n\[][^\n]*\n)*\n?', "", t, count=1)
    assert n == 1, "fat over the hepatocystic triangle"
    for name in ("cystic duct", "common hepatic duct", "common bile duct", "cystic artery"):
        t, n = re.subn(r'\[\[context_organs\]\]\nname = "' + re.escape(name) + r'"[^\n]*\n(?:[^\n\[][^\n]*\n)*\n?', "", t, count=1)
        assert n == 1, name
    return t

# What the cleared triangle shows behind it, so the view through it is tissue, not a void: the
# portal vein at the back of the hepatoduodenal ligament (posterior and medial to the common
# ducts, behind the duodenum's first part) and the posterior peritoneum further back. Drawn only
# (solid = false): nothing rests on them. The default's view does not look through the triangle,
# so they are the variants' alone (tests/scenario/calot_variant_scenarios_test.cpp).
backdrop = """
[[context_organs]]
name = "portal vein"   # behind the common ducts, seen through the cleared triangle
shape = "tube"
points_m = [[0.0260, -0.0500, 0.0600], [0.0150, -0.0680, 0.0420], [0.0050, -0.1050, 0.0150]]
radius_m = 0.006
rgb = [0.47, 0.34, 0.44]
solid = false

[[context_organs]]
name = "posterior peritoneum"   # over the vena cava and the right kidney, the back of the view
shape = "ellipsoid"
centre_m = [-0.0100, -0.1400, 0.0600]
semi_axes_m = [0.1600, 0.0150, 0.1200]
rgb = [0.78, 0.60, 0.52]
solid = false
"""

def with_backdrop(t):
    i = t.index("[calot_triangle]")
    return t[:i] + backdrop.lstrip("\n") + "\n" + t[i:]

for key, (variant, note, tubes, task) in variants.items():
    t = text
    # header: our own comment block in place of the default's
    body = t[t.index("[scenario]"):]
    header = ("# Vesica scenario: Calot's triangle (%s), issue 36.\n"
              "# The default scenario (cholecystectomy.toml) with the hepatocystic triangle simulated:\n# %s.\n"
              "# The right hand's hook is exchanged (T) for the clip applier and the scissors; B opens and\n"
              "# closes their jaws. The laparoscope looks at the triangle from closer in. Otherwise the\n"
              "# default, line for line\n"
              "# (tests/scenario/calot_variant_scenarios_test.cpp).\n"
              "# World frame = patient: x left, y anterior, z cranial; metres.\n\n") % (variant, note)
    body = re.sub(r'name = "Laparoscopic cholecystectomy"', 'name = "Laparoscopic cholecystectomy, Calot\'s triangle (%s)"' % variant, body, count=1)
    body = re.sub(r'description = "[^"]*"', 'description = "%s"' % task.replace('"', "'"), body, count=1)
    body, n = re.subn(r'(name = "hook"\nkind = "cautery_hook"\ntrocar = "right"\n(?:[^\n\[][^\n]*\n)*?initial_insertion_m = [^\n]*\n)',
                      r'\1exchange = ["clip_applier", "scissors"]   # T: the hook, then the clip applier, then the scissors\n', body, count=1)
    assert n == 1
    body = without_context_tubes(body)
    body = aimed_at_the_triangle(body)
    body = body.rstrip("\n") + "\n" + triangle(variant, neck, tubes, note)
    body = with_backdrop(body)
    open(root + "/data/scenarios/calot-%s.toml" % key, "w").write(header + body)
    print("wrote calot-%s.toml" % key)
