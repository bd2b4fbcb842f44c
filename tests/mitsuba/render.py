"""Renders one of tests/mitsuba.rs's scenes with Mitsuba 3 (scalar_rgb, its path
integrator) to a linear EXR: the independent reference prism's path tracer is compared
with.

    python render.py SCENE SAMPLES MAX_DEPTH OUT.exr SKY.exr [WIDTH HEIGHT]

(the sky image, and cube.obj beside it, are the files tests/mitsuba.rs writes; the image is
64×48 unless WIDTH and HEIGHT say otherwise). It prints the seconds `mi.render` took, which
`prism bench path-tracing` reads.

Each scene is the one tests/mitsuba.rs gives prism, written out again for Mitsuba: the same
room (thin boxes, so that both renderers see the same solid walls), camera, materials and
light, the light in the physical units docs/effects.md gives for prism's lights. prism's
`max_depth` bounces are Mitsuba's max_depth + 2 (the caller passes Mitsuba's).
"""

import math
import sys
import time

import mitsuba as mi

mi.set_variant("scalar_rgb")
T = mi.ScalarTransform4f

WIDTH, HEIGHT = 64, 48


def box(lo, hi, bsdf):
    center = [(a + b) / 2 for a, b in zip(lo, hi)]
    half = [(b - a) / 2 for a, b in zip(lo, hi)]
    return {"type": "cube", "to_world": T().translate(center).scale(half), "bsdf": bsdf}


def diffuse(r, g, b):
    return {"type": "diffuse", "reflectance": {"type": "rgb", "value": [r, g, b]}}


BLACK = diffuse(0, 0, 0)

# prism's `reflectivity = 0.9` with `roughness = 0.5`: a GGX mirror of α = 0.25.
ROUGH_METAL = {
    "type": "roughconductor",
    "material": "none",
    "distribution": "ggx",
    "alpha": 0.25,
    "specular_reflectance": {"type": "rgb", "value": [0.9, 0.9, 0.9]},
}


def room():
    """The room of every scene: x and z in -1..1, y in 0..2, open at the front (+z)."""
    white, red, green = diffuse(0.7, 0.7, 0.7), diffuse(0.6, 0.1, 0.1), diffuse(0.1, 0.5, 0.1)
    return {
        "floor": box([-1.1, -0.1, -1.1], [1.1, 0, 1.1], white),
        "ceiling": box([-1.1, 2, -1.1], [1.1, 2.1, 1.1], white),
        "back": box([-1.1, -0.1, -1.1], [1.1, 2.1, -1], white),
        "left": box([-1.1, -0.1, -1.1], [-1, 2.1, 1.1], red),
        "right": box([1, -0.1, -1.1], [1.1, 2.1, 1.1], green),
        "block": box([-0.7, 0, -0.6], [-0.2, 0.8, -0.1], white),
    }


def rectangle_light(radiance):
    """A 0.5 × 0.5 square 0.2 under the ceiling, glowing on both sides (prism's area
    lights do): two one-sided rectangles back to back, the upper one 10⁻⁴ above the
    other, so that each ray meets the side facing it first."""
    square = lambda y, angle: {
        "type": "rectangle",
        "to_world": T().translate([0, y, 0]).rotate([1, 0, 0], angle).scale([0.25, 0.25, 1]),
        "bsdf": BLACK,
        "emitter": {"type": "area", "radiance": {"type": "rgb", "value": radiance}},
    }
    return {"light_down": square(1.8, 90), "light_up": square(1.8001, -90)}


def environment(sky):
    """The environment scene: a grey floor, a matte ball, a rough metal ball and a glass
    ball under the sky image `sky` (linear values: prism's 8-bit PNG divided by 255).
    Mitsuba's u = 0 lies where prism's u = 1/2 does (along −z): turned 180° about y, the
    two skies line up."""
    return {
        "type": "scene",
        "integrator": {"type": "path"},
        "camera": camera([0, 1.2, 4], [0, 0.5, 0]),
        "sky": {
            "type": "envmap",
            "filename": sky,
            "to_world": T().rotate([0, 1, 0], 180),
        },
        "floor": box([-3, -0.1, -3], [3, 0, 3], diffuse(0.5, 0.5, 0.5)),
        "matte": {"type": "sphere", "center": [-1.1, 0.5, 0], "radius": 0.5, "bsdf": diffuse(0.8, 0.8, 0.8)},
        "metal": {
            "type": "sphere",
            "center": [0, 0.5, -0.3],
            "radius": 0.5,
            "bsdf": ROUGH_METAL,
        },
        "glass": {
            "type": "sphere",
            "center": [1.1, 0.5, 0],
            "radius": 0.5,
            "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0},
        },
    }


def camera(origin, target):
    return {
        "type": "perspective",
        "fov": 40,
        "fov_axis": "y",
        "to_world": T().look_at(origin=origin, target=target, up=[0, 1, 0]),
        "film": {
            "type": "hdrfilm",
            "width": WIDTH,
            "height": HEIGHT,
            "rfilter": {"type": "box"},
            "pixel_format": "rgb",
        },
    }


def scene(name):
    s = {
        "type": "scene",
        "integrator": {"type": "path"},
        "camera": camera([0, 1, 3.4], [0, 1, 0]),
    }
    s.update(room())
    if name == "sphere_light":
        # prism: colour [1, 0.9, 0.8], intensity 1, radius 0.15: radiance C·g/r².
        r = 0.15
        s["lamp"] = {
            "type": "sphere",
            "center": [0, 1.6, 0],
            "radius": r,
            "bsdf": BLACK,
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [c / r**2 for c in (1, 0.9, 0.8)]}},
        }
    elif name == "rectangle_light":
        # prism: colour [1, 1, 1], intensity 1, area 0.25: radiance π·C·g/A on each side.
        s.update(rectangle_light([math.pi / 0.25] * 3))
    elif name == "point_light":
        # prism: colour [1, 0.95, 0.9], intensity 2: radiant intensity π·C·g.
        s["lamp"] = {
            "type": "point",
            "position": [0, 1.7, 0.2],
            "intensity": {"type": "rgb", "value": [math.pi * 2 * c for c in (1, 0.95, 0.9)]},
        }
    elif name == "glass_and_metal":
        s.update(rectangle_light([math.pi / 0.25] * 3))
        s["glass"] = {
            "type": "sphere",
            "center": [0.4, 0.35, 0.3],
            "radius": 0.35,
            "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0},
        }
        s["metal"] = {
            "type": "sphere",
            "center": [-0.45, 1.1, -0.35],
            "radius": 0.3,
            "bsdf": ROUGH_METAL,
        }
    elif name == "rough_glass":
        # prism: Fresnel glass with `roughness` 0.5 and 0.25: GGX of α = roughness².
        s.update(rectangle_light([math.pi / 0.25] * 3))
        for key, center, roughness in (
            ("frosted", [0.4, 0.35, 0.3], 0.5),
            ("misted", [-0.45, 0.9, -0.35], 0.25),
        ):
            s[key] = {
                "type": "sphere",
                "center": center,
                "radius": 0.35 if key == "frosted" else 0.3,
                "bsdf": {
                    "type": "roughdielectric",
                    "distribution": "ggx",
                    "alpha": roughness * roughness,
                    "int_ior": 1.5,
                    "ext_ior": 1.0,
                },
            }
    elif name == "glowing_objects":
        # prism: a ball and a mesh (cube.obj, which the test writes beside the sky) whose
        # material has `emission`, black otherwise: their surfaces glow, found both by
        # scattered rays and by their own samples.
        s["ball"] = {
            "type": "sphere",
            "center": [0.45, 1.5, -0.3],
            "radius": 0.2,
            "bsdf": BLACK,
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [6, 5, 3.5]}},
        }
        s["cube"] = {
            "type": "obj",
            "filename": CUBE,
            "face_normals": True,
            "to_world": T().translate([-0.5, 1.6, 0.3]).scale(0.15),
            "bsdf": BLACK,
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [2, 4, 6]}},
        }
        # prism: a glowing box turned 30° about y (an instance of a box, sampled by area
        # through its transform) and a glowing capped cylinder (its caps here two discs).
        red = {"type": "area", "radiance": {"type": "rgb", "value": [5, 1.5, 1]}}
        green = {"type": "area", "radiance": {"type": "rgb", "value": [1, 4, 1.5]}}
        s["box"] = {
            "type": "cube",
            "to_world": T().translate([0.35, 0.15, 0.4]).rotate([0, 1, 0], 30).scale(0.15),
            "bsdf": BLACK,
            "emitter": red,
        }
        s["tube"] = {
            "type": "cylinder",
            "p0": [-0.45, 0.7, -0.4],
            "p1": [-0.45, 1.1, -0.4],
            "radius": 0.1,
            "bsdf": BLACK,
            "emitter": green,
        }
        for key, y, angle in (("top", 1.1, -90), ("bottom", 0.7, 90)):
            s[key] = {
                "type": "disk",
                "to_world": T().translate([-0.45, y, -0.4]).rotate([1, 0, 0], angle).scale(0.1),
                "bsdf": BLACK,
                "emitter": green,
            }
    else:
        raise SystemExit(f"no scene {name!r}")
    return s


CUBE = None


def main():
    global CUBE
    name, samples, max_depth, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    CUBE = sys.argv[5].replace("sky.exr", "cube.obj")
    global WIDTH, HEIGHT
    if len(sys.argv) > 7:
        WIDTH, HEIGHT = int(sys.argv[6]), int(sys.argv[7])
    s = environment(sys.argv[5]) if name == "environment" else scene(name)
    s["integrator"]["max_depth"] = max_depth
    loaded = mi.load_dict(s)
    start = time.perf_counter()
    image = mi.render(loaded, spp=samples)
    print(f"{time.perf_counter() - start:.6f}")
    mi.util.write_bitmap(out, image)


if __name__ == "__main__":
    main()
