// Scenes with known radiance, built in code: a Lambert plane under one punctual light, and a
// closed emissive box (the "furnace"), whose radiance is a geometric series of its albedo.
#pragma once
#include "core/scene/scene.h"

namespace sst::test {

// A square plane z = 0 of half-size `half`, normal +z, Lambert albedo `albedo`, camera looking
// straight down from (0, 0, camera_height) with the given vertical field of view.
Scene lambert_plane(float albedo, float half, float camera_height, float yfov);

// A closed axis-aligned cube of side `side` centred at the origin; every face diffuse with
// `albedo` and emitting `emission` from both sides; camera at the centre looking down -z.
Scene emissive_box(float albedo, float emission, float side);

// A closed axis-aligned cube of side `side` centred at the origin, every face diffuse (double-
// sided) with RGB albedo `albedo` and no emission; camera at the centre looking down -z.
Scene diffuse_box(vec3 albedo, float side);

// A closed sphere of radius `radius` centred at the origin: a UV sphere of `rings` x 2 rings
// quads with smooth (outward) normals, diffuse (double-sided) with albedo `albedo`; camera at the
// centre looking down -z.
Scene diffuse_sphere(float albedo, float radius, int rings);

// A punctual light; `direction` is normalised (the direction the light travels).
PunctualLight punctual_light(LightType type, vec3 position, vec3 direction, vec3 intensity);

// Adds triangle (a, b, c) (normal by winding) with a new black emissive material, then refreshes
// the scene bounds.
void add_emissive_triangle(Scene& scene, vec3 a, vec3 b, vec3 c, vec3 emission, bool double_sided);

// Many small lights over a floor, for the light samplers' tests: a 10 m diffuse floor (y = 0,
// double-sided, albedo 0.5) and a ceiling (y = 4), `triangles` small emissive triangles (sides
// 2-20 cm) at random places and orientations in [-4, 4] x [0.2, 3.8] x [-4, 4] with four emissive
// materials of different radiance (two one-sided, two double-sided), `points` point and `spots`
// spot lights (random aims and cones), and one directional light when `sun` is set; a camera
// looking down at the floor. Everything from `seed`.
Scene many_lights(uint32_t seed, int triangles, int points, int spots, bool sun);

// A wide field of many small lights, for the light trees' tests: a 40 m diffuse ground (y = 0),
// `quads` small double-sided emissive quads (sides 5-15 cm, two triangles each) at random places
// in [-19.5, 19.5] x [0.3, 3] x [-19.5, 19.5] and random orientations, in 32 materials whose
// radiance spans two orders of magnitude (2-200), `points` point lights (1-30 W/sr) and `spots`
// spot lights (30-300 W/sr, aimed down within 30 degrees); no directional light. From `seed`.
Scene light_field(uint32_t seed, int quads, int points, int spots);

// Thin geometry in front of a wall, for GI-1.0's side cache: a floor (y = 0, 8 x 6 m), a back wall
// (z = -2.5, 3 m high) and `slats` vertical double-sided slats (`width` wide, 2.5 m high) 1 m in
// front of it, `spacing` apart and centred on x = 0, all diffuse (albedo 0.6), lit by a point light
// at (0, 2.5, 0.5); a camera at (0, 1.2, 2.5) looking down -z (field of view 1 rad, aspect 4/3).
// With `ceiling`, a ceiling at y = 3 closes the view: every pixel sees a surface.
Scene thin_slats(int slats, float width, float spacing, bool ceiling = false);

// Scales every position, light and camera of a scene by s (scene-scale tests).
void scale_scene(Scene& scene, float s);

}  // namespace sst::test
