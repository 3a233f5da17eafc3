// pc_synth: synthetic fruit-tree clouds with ground truth, as reconstructors export them.
#include <numeric>

#include <nlohmann/json.hpp>

#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/scenes/render.h>

namespace sy = pc::scenes;

namespace {

std::array<std::uint8_t, 3> parse_rgb(const std::string& option, const std::string& text) {
    const auto t = pc::cli::parse_triple(option, text);
    std::array<std::uint8_t, 3> out{};
    for (int c = 0; c < 3; ++c) {
        if (!(t[c] >= 0 && t[c] <= 255) || t[c] != static_cast<int>(t[c])) {
            throw pc::InvalidArgument("--" + option + ": channels must be integers 0..255, got '" +
                                      text + "'");
        }
        out[c] = static_cast<std::uint8_t>(t[c]);
    }
    return out;
}

std::string truth_json(const std::string& species,
                       const sy::SceneParams& sp,
                       const sy::RenderParams& rp,
                       const sy::Scene& scene,
                       const sy::Rendered& r) {
    nlohmann::ordered_json fruits = nlohmann::ordered_json::array();
    std::size_t present = 0;
    for (std::size_t f = 0; f < scene.fruits.size(); ++f) {
        const auto& x = scene.fruits[f];
        present += r.fruit_points[f] > 0;
        sy::Vec3 centre = x.centre;
        for (int a = 0; a < 3; ++a) {
            centre[a] = centre[a] * rp.scale + rp.offset[a];
        }
        nlohmann::ordered_json fruit = {{"id", f + 1},
                                        {"centre", centre},
                                        {"radius", x.radius * rp.scale},
                                        {"bunch", x.bunch},
                                        {"points", r.fruit_points[f]}};
        if (x.blush_from <= 1) {  // bicoloured: the share of its surface blushed
            fruit["blush"] = (1 - x.blush_from) / 2;
        }
        if (!x.round()) {  // a spheroid: radius is the same-volume sphere's
            fruit["aspect"] = x.aspect;
            fruit["axis"] = x.axis;
        }
        fruits.push_back(fruit);
    }
    nlohmann::ordered_json j;
    j["generator"] = "pc_synth";
    j["species"] = species;
    j["mode"] = sy::mode_name(rp.mode);
    j["seed"] = sp.seed;
    j["voxel"] = rp.voxel;
    j["colors"] = sy::colors_name(rp.colors);
    j["scale"] = rp.scale;
    j["offset"] = rp.offset;
    j["fruit_count"] = scene.fruits.size();
    j["fruit_present"] = present;
    j["bunch_count"] = scene.bunch_count;
    j["points"] = r.xyz.size();
    j["fruit_points"] =
        std::accumulate(r.fruit_points.begin(), r.fruit_points.end(), std::uint64_t{0});
    j["fruits"] = fruits;
    if (!scene.branches.empty()) {  // the wood: truncated cones, in the written units
        const auto at = [&](const sy::Vec3& v) {
            return sy::Vec3{v[0] * rp.scale + rp.offset[0], v[1] * rp.scale + rp.offset[1],
                            v[2] * rp.scale + rp.offset[2]};
        };
        nlohmann::ordered_json wood = nlohmann::ordered_json::array();
        for (const auto& b : scene.branches) {
            wood.push_back({{"from", at(b.from)},
                            {"to", at(b.to)},
                            {"r_from", b.r_from * rp.scale},
                            {"r_to", b.r_to * rp.scale}});
        }
        j["branches"] = wood;
    }
    return j.dump(1) + "\n";
}

}  // namespace

int main(int argc, char** argv) {
    std::string species = "peach", truth;
    sy::SceneParams sp = sy::species(species);
    sy::RenderParams rp;
    pc::cli::Tool tool(
        "pc_synth",
        "synthetic fruit-tree cloud with ground truth (x y z rgb gt_instance), as an explicit, "
        "implicit or degraded reconstruction exports it");
    tool.no_input();
    tool.option(
        "species", species,
        [&](const std::string& s) {
            const auto seed = sp.seed;
            sp = sy::species(s);  // the species first; flags given after it override its values
            sp.seed = seed;
            species = s;
        },
        "peach (152 fruit, separated), apple (283, bunches of 1-3), plum (745, bunches of 3-8 "
        "touching)");
    tool.option(
        "mode", sy::mode_name(rp.mode), [&](const std::string& s) { rp.mode = sy::parse_mode(s); },
        "explicit (solid voxels), implicit (visible surfaces, NeRF-like), degraded (poor masks); "
        "sampled off the lattice: surface (random on the surface), sfm (structure from motion: "
        "uneven, holes, duplicates), stripes (scan lines), volume (random inside)");
    tool.option(
        "colors", sy::colors_name(rp.colors),
        [&](const std::string& s) { rp.colors = sy::parse_colors(s); },
        "natural (fruit-rgb, green leaves, dark ground) or mask (fruit white, the rest black)");
    tool.option("seed", &sp.seed, "random seed: the same seed gives the same bytes");
    tool.option("truth", &truth,
                "also write the fruit (id, centre, radius, bunch, points) as JSON here");
    tool.option("fruit-count", &sp.fruit_count, "number of fruit (the ground-truth count)");
    tool.option("fruit-radius", &sp.fruit_radius, "mean fruit radius, m");
    tool.option("radius-spread", &sp.radius_spread, "radii uniform in radius x (1 +- this)");
    tool.option("aspect", &sp.aspect,
                "fruit shape: polar / equatorial half axis of a spheroid (1 sphere, 0.85 apple, "
                "1.4 lemon); the radius is the same-volume sphere's");
    tool.option("aspect-spread", &sp.aspect_spread,
                "aspects uniform in aspect x (1 +- this); axes in random directions");
    tool.option("bunch-min", &sp.bunch_min, "least fruit per bunch");
    tool.option("bunch-max", &sp.bunch_max, "most fruit per bunch");
    tool.option("touch-gap", &sp.touch_gap,
                "gap between touching fruit of a bunch: uniform in [0, this], m");
    tool.option("overlap", &sp.overlap,
                "fruit of a bunch may interpenetrate by up to this x the smaller radius");
    tool.option("separation", &sp.separation, "least gap between fruit of different bunches, m");
    tool.option("canopy", &sp.canopy, "half axes of the canopy ellipsoid, m");
    tool.option("shell", &sp.shell,
                "bunches sit between this fraction of the canopy radius and its edge");
    tool.option("leaf-density", &sp.leaf_density,
                "leaves per m^3 of canopy (occluders; some leak as points)");
    tool.option("leaf-radius", &sp.leaf_radius, "mean leaf radius, m");
    tool.option(
        "fruit-rgb", "240,165,95",
        [&](const std::string& s) { sp.fruit_rgb = parse_rgb("fruit-rgb", s); },
        "fruit colour R,G,B (0..255); default by species");
    tool.option(
        "blush-rgb", "185,35,45",
        [&](const std::string& s) { sp.blush_rgb = parse_rgb("blush-rgb", s); },
        "bicoloured fruit: blush colour R,G,B (0..255), over a cap of each fruit");
    tool.option("blush-min", &sp.blush_min,
                "bicoloured fruit: least share of a fruit's surface blushed (0..1)");
    tool.option("blush-max", &sp.blush_max,
                "bicoloured fruit: largest share blushed (0: one colour, the default)");
    tool.option("branches", &sp.branches,
                "wood: a trunk forking into this many main branches, two side branches each (0: "
                "no wood)");
    tool.option("trunk-radius", &sp.trunk_radius, "wood: trunk radius, m");
    tool.option(
        "wood-rgb", "100,80,60",
        [&](const std::string& s) { sp.wood_rgb = parse_rgb("wood-rgb", s); },
        "wood: bark colour R,G,B (0..255)");
    tool.option("wood-leak", &rp.wood_leak, "wood: fraction of the branches exported");
    tool.option("voxel", &rp.voxel, "voxel edge, m: explicit occupancy and surface sampling");
    tool.option("cameras", &rp.cameras, "implicit: cameras on three rings around the canopy");
    tool.option("min-views", &rp.min_views,
                "implicit: a surface voxel needs this many cameras seeing it");
    tool.option("surface-noise", &rp.surface_noise,
                "implicit: sigma of the point jitter, in voxels");
    tool.option("bridge-gap", &rp.bridge_gap,
                "implicit: bridge fruit closer than this x the smaller radius");
    tool.option("bridge-probability", &rp.bridge_probability,
                "implicit: chance of a noise bridge per close pair");
    tool.option("floaters", &rp.floaters, "implicit: floater blobs per fruit");
    tool.option("recall", &rp.recall, "degraded: mean fraction of each fruit kept by the masks");
    tool.option("noise", &rp.noise,
                "sampled modes: sigma of each point's jitter, as a fraction of the fruit radius");
    tool.option("holes", &rp.holes, "sfm: mean number of empty caps per fruit");
    tool.option("duplicates", &rp.duplicates, "sfm: fraction of points written twice");
    tool.option("density-spread", &rp.density_spread, "sfm: sigma of each fruit's log density");
    tool.option(
        "shading", &rp.shading,
        "sampled modes: 0 flat colour .. 1 black where a surface faces away from the light");
    tool.option("color-noise", &rp.color_noise,
                "sampled modes and wood: sigma of a Gaussian added to each colour channel "
                "(0..255), as colours vary between the views of SfM and NeRF");
    tool.option("scale", &rp.scale,
                "units: written coordinates = metres x scale + offset (1000: millimetres)");
    tool.option("offset", &rp.offset, "units: added after --scale");
    tool.option("leaf-leak", &rp.leaf_leak, "fraction of leaves exported as green points");
    tool.option("background", &rp.background, "dark ground points, as a fraction of fruit points");
    tool.option("outliers", &rp.outliers, "bright sparse outliers, as a fraction of fruit points");
    tool.epilog("\nModels, defaults and their limits: docs/tools/pc_synth.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        rp.seed = sp.seed;
        const sy::Scene scene = sy::make_scene(sp);
        const sy::Rendered r = sy::render(scene, rp);
        io.note(std::to_string(scene.fruits.size()) + " fruit in " +
                std::to_string(scene.bunch_count) + " bunches, " +
                std::to_string(scene.leaves.size()) + " leaves, " +
                std::to_string(scene.branches.size()) + " pieces of wood, " +
                std::to_string(r.xyz.size()) + " points");
        if (!truth.empty()) {
            pc::cli::write_text_file(truth, truth_json(species, sp, rp, scene, r));
        }
        io.write(sy::to_blob(r));
    });
}
