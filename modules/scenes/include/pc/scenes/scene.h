#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pc::scenes {

using Vec3 = std::array<double, 3>;

/// One fruit: a spheroid about the unit `axis`, its polar half axis `aspect` × its equatorial
/// one (below 1 oblate as apples and tomatoes, above 1 prolate as lemons and pears), a sphere when
/// `aspect` is 1. `radius` is the radius of the sphere of the same volume. `bunch` numbers the
/// group of touching fruit it hangs in (0-based). A point of the fruit is written at(d, depth):
/// the unit sphere's direction d stretched to the spheroid, depth = radius on the surface.
struct Fruit {
    Vec3 centre{};
    double radius = 0;
    std::uint32_t bunch = 0;
    double aspect = 1;
    Vec3 axis{0, 0, 1};
    /// Bicoloured fruit: the points whose direction from the centre lies within the cap about
    /// `blush_side` whose cosine is at least `blush_from` wear the scene's blush colour (2: none)
    Vec3 blush_side{0, 0, 1};
    double blush_from = 2;

    [[nodiscard]] bool round() const { return aspect == 1; }
    /// centre + (depth / radius) × (the spheroid's point for the unit direction d)
    [[nodiscard]] Vec3 at(const Vec3& d, double depth) const;
    /// The outward unit normal at at(d, radius).
    [[nodiscard]] Vec3 normal(const Vec3& d) const;
    /// q's depth relative to the surface: 1 on it, below 1 inside (|q - centre| / radius for a
    /// sphere).
    [[nodiscard]] double level(const Vec3& q) const;
    /// The half width along the unit direction u (the support function; radius for a sphere).
    [[nodiscard]] double reach(const Vec3& u) const;
    /// The largest and the smallest half axis.
    [[nodiscard]] double largest() const;
    [[nodiscard]] double smallest() const;
    /// The surface area (Knud Thomsen's formula, within 1.1 %; exact for a sphere).
    [[nodiscard]] double area() const;
};

/// A leaf: a flat disc. Leaves occlude fruit from the cameras and leak into exports as clutter.
struct Leaf {
    Vec3 centre{};
    Vec3 normal{0, 0, 1};
    double radius = 0;
};

/// A piece of wood: a truncated cone from `from` (radius `r_from`) to `to` (radius `r_to`). The
/// trunk and branches of the tree; the renderers drop its points that lie inside a fruit.
struct Branch {
    Vec3 from{}, to{};
    double r_from = 0, r_to = 0;
};

/// The layout of a synthetic fruit tree, in metres, canopy centred on the origin.
struct Scene {
    std::vector<Fruit> fruits;
    std::vector<Leaf> leaves;
    std::vector<Branch> branches;  ///< the trunk first, then branches and twigs (empty: no wood)
    std::array<std::uint8_t, 3> wood_rgb{100, 80, 60};
    Vec3 canopy{1, 1, 1};  ///< half axes of the canopy ellipsoid
    std::array<std::uint8_t, 3> fruit_rgb{240, 165, 95};
    std::array<std::uint8_t, 3> blush_rgb{185, 35, 45};
    std::uint32_t bunch_count = 0;

    /// The colour of fruit `f` at point q: fruit_rgb, or blush_rgb on its blushed side.
    [[nodiscard]] const std::array<std::uint8_t, 3>& fruit_colour(std::size_t f,
                                                                  const Vec3& q) const;
};

/// Parameters of make_scene(). species() fills them for the paper's three datasets.
struct SceneParams {
    std::uint32_t fruit_count = 152;  ///< fruit in the scene (the ground-truth count)
    double fruit_radius = 0.035;      ///< mean fruit radius, m
    double radius_spread = 0.1;       ///< radii uniform in radius·(1 ± spread)
    std::uint32_t bunch_min = 1;      ///< fruit per bunch, uniform in [bunch_min, bunch_max]
    std::uint32_t bunch_max = 1;
    double touch_gap = 0.002;  ///< gap between touching fruit of a bunch, uniform in [0, this]
    double overlap = 0;  ///< fruit of a bunch may interpenetrate by up to this × the smaller radius
    double separation = 0.03;    ///< least gap between fruit of different bunches
    Vec3 canopy{1.0, 1.0, 0.8};  ///< half axes of the canopy ellipsoid, m
    double shell = 0.5;          ///< bunches sit between this fraction of the canopy and its edge
    double leaf_density = 300;   ///< leaves per m³ of canopy
    double leaf_radius = 0.035;  ///< mean leaf radius, m
    std::array<std::uint8_t, 3> fruit_rgb{240, 165, 95};
    double aspect = 1;  ///< mean polar / equatorial half axis of the fruit (1 = spheres)
    double aspect_spread =
        0;  ///< aspects uniform in aspect·(1 ± spread), axes in random directions
    /// Wood: a trunk from the ground (0.3 m below the canopy) forking into this many main
    /// branches, each with two side branches (0: no wood, the scene as before)
    std::uint32_t branches = 0;
    double trunk_radius = 0.05;  ///< m; main branches start at half of it, twigs end at 4 mm
    std::array<std::uint8_t, 3> wood_rgb{100, 80, 60};  ///< bark (grey-brown)
    /// Bicoloured fruit (a red blush over a yellow or green ground colour, as on Fuji and Gala
    /// apples, peaches and mangoes): each fruit wears blush_rgb over a cap of its surface whose
    /// share is uniform in [blush_min, blush_max], on a side of its own (0, 0: one colour; drawn
    /// from a stream of their own, so that scenes without blush keep their bytes)
    std::array<std::uint8_t, 3> blush_rgb{185, 35, 45};
    double blush_min = 0, blush_max = 0;
    std::uint64_t seed = 1;

    void validate() const;  ///< throws pc::InvalidArgument naming the field
};

/// Names accepted by species(): peach, apple, plum.
[[nodiscard]] const std::vector<std::string>& species_names();
/// The paper's datasets in kind: peach (152 fruit, well separated), apple (283, bunches of 1-3),
/// plum (745, bunches of 3-8 touching fruit). Throws pc::InvalidArgument for another name.
[[nodiscard]] SceneParams species(std::string_view name);

/// Places the fruit bunch by bunch (rejection sampling: fruit never overlap, touching fruit of a
/// bunch are 0..touch_gap apart, other bunches at least `separation` away), scatters leaves and
/// grows the wood (its own random stream: fruit and leaves do not depend on it). Deterministic for
/// a seed. Throws pc::InvalidArgument when the canopy cannot hold the fruit.
[[nodiscard]] Scene make_scene(const SceneParams& params);

}  // namespace pc::scenes
