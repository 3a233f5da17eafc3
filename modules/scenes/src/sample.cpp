// The sampled modes: points drawn at random on (or in) each fruit instead of on the voxel
// lattice, for the sampling kinds real reconstructions have (splats and meshes, structure from
// motion, scan lines, solid occupancy off the lattice).
#include <cmath>
#include <limits>

#include <pc/core/error.h>

#include "emit.h"

namespace pc::scenes::detail {

namespace {

std::uint64_t poisson(double mean, Rng& rng) {
    const double limit = std::exp(-mean);
    std::uint64_t k = 0;
    for (double prod = rng.uniform(); prod > limit; prod *= rng.uniform()) {
        ++k;
    }
    return k;
}

/// Draws the points of every fruit for the sampled modes.
class Sampler {
public:
    Sampler(const Scene& s, const RenderParams& p, Rng& rng, Rendered& out)
        : s_(s), p_(p), rng_(rng), paint_(p, rng, 7), out_(out), members_(s.bunch_count) {
        for (std::size_t f = 0; f < s.fruits.size(); ++f) {
            members_[s.fruits[f].bunch].push_back(static_cast<std::uint32_t>(f));
        }
        const double a = rng_.uniform(0, 2 * kPi);  // the scanner's side (stripes)
        toward_scanner_ = {std::cos(a), std::sin(a), 0};
        across_ = {-std::sin(a), std::cos(a), 0};
    }

    void fruit(std::size_t f) {
        const Fruit& x = s_.fruits[f];
        const double tone = rng_.uniform(0.85, 1.1), v = p_.voxel, r = x.radius;
        const auto emit = [&](const Vec3& d, double depth, std::size_t copies) {
            Vec3 q = x.at(d, depth);
            if (inside_other(f, q, depth / r)) {
                return;
            }
            for (auto& c : q) {
                c += p_.noise * r * rng_.normal();
            }
            const std::uint32_t rgb = paint_.fruit(s_.fruit_colour(f, q), tone, x.normal(d));
            for (std::size_t k = 0; k < copies; ++k) {
                add_point(out_, q, rgb, static_cast<std::uint32_t>(f + 1));
            }
        };
        const double area = x.area() / (v * v);
        switch (p_.mode) {
            case Mode::kSurface:
                for (auto n = std::llround(area); n > 0; --n) {
                    emit(on_surface(x), r, 1);
                }
                break;
            case Mode::kVolume:  // the sphere's volume: a spheroid's is the same
                for (auto n = std::llround(4 * kPi * r * r / (v * v) * r / (3 * v)); n > 0; --n) {
                    emit(rng_.direction(), r * std::cbrt(rng_.uniform()), 1);
                }
                break;
            case Mode::kSfm:
                sfm(f, area, emit);
                break;
            case Mode::kStripes:
                stripes(f, emit);
                break;
            default:
                throw InvalidArgument("render: not a sampled mode");
        }
    }

    /// Leaked leaves: uniform random points on the disc at the point spacing.
    void leaves() {
        const double v = p_.voxel;
        for (const Leaf& l : s_.leaves) {
            if (rng_.uniform() >= p_.leaf_leak) {
                continue;
            }
            const auto [e1, e2] = basis(l.normal);
            for (auto n = std::llround(kPi * l.radius * l.radius / (v * v)); n > 0; --n) {
                const double rho = l.radius * std::sqrt(rng_.uniform()),
                             phi = rng_.uniform(0, 2 * kPi);
                Vec3 q = l.centre;
                for (int a = 0; a < 3; ++a) {
                    q[a] += rho * (std::cos(phi) * e1[a] + std::sin(phi) * e2[a]) +
                            p_.noise * v * rng_.normal();
                }
                add_point(out_, q, paint_.leaf(l.normal), 0);
            }
        }
    }

private:
    /// A direction of the unit sphere whose image on fruit x is uniform over x's surface: any
    /// direction for a sphere; for a spheroid, kept with probability the stretch of the area there
    /// over the largest stretch (rejection).
    [[nodiscard]] Vec3 on_surface(const Fruit& x) {
        for (;;) {
            const Vec3 d = rng_.direction();
            if (x.round()) {
                return d;
            }
            const double along = dot(d, x.axis), across = std::max(0.0, 1 - along * along);
            const double stretch = std::sqrt(across + along * along / (x.aspect * x.aspect));
            if (rng_.uniform() * std::max(1.0, 1 / x.aspect) < stretch) {
                return d;
            }
        }
    }

    /// True when q (at `relative` × the way from fruit f's centre to its surface) lies deeper
    /// inside another fruit of the bunch than in f: interpenetrating fruit show only their outer
    /// surfaces.
    [[nodiscard]] bool inside_other(std::size_t f, const Vec3& q, double relative) const {
        for (auto g : members_[s_.fruits[f].bunch]) {
            if (g != f && s_.fruits[g].level(q) < relative) {
                return true;
            }
        }
        return false;
    }

    /// Structure from motion: cameras circle the tree, so each fruit's outer side is dense and its
    /// inner side sparse (down to a tenth); each fruit's density varies (log-normal); holes are
    /// empty caps; some points are written twice.
    template <class Emit>
    void sfm(std::size_t f, double area, Emit& emit) {
        const Fruit& x = s_.fruits[f];
        const double h = std::hypot(x.centre[0], x.centre[1]);
        const Vec3 outward = h > 1e-9 ? Vec3{x.centre[0] / h, x.centre[1] / h, 0} : Vec3{1, 0, 0};
        const double density = std::clamp(std::exp(p_.density_spread * rng_.normal()), 0.2, 3.0);
        std::vector<std::pair<Vec3, double>> holes;
        for (auto k = poisson(p_.holes, rng_); k > 0; --k) {
            holes.emplace_back(rng_.direction(), std::cos(std::asin(rng_.uniform(0.2, 0.45))));
        }
        for (auto n = std::llround(area * density); n > 0; --n) {
            const Vec3 d = on_surface(x);
            const double keep = 0.1 + 0.9 * std::max(0.0, dot(x.normal(d), outward));
            bool in_hole = false;
            for (const auto& [centre, cosine] : holes) {
                in_hole = in_hole || dot(d, centre) > cosine;
            }
            if (rng_.uniform() < keep && !in_hole) {
                emit(d, x.radius, rng_.uniform() < p_.duplicates ? 2 : 1);
            }
        }
    }

    /// Scan lines: vertical planes `voxel` apart across the scanner's view, points a third of that
    /// apart along each line, only on the side facing the scanner. A plane at t from the centre
    /// meets the unit sphere that the fruit stretches (x = centre + A y, |y| = 1) in the circle
    /// y · w = t / L, w = A across / L, L = |A across| (for a sphere w = across, L = r).
    template <class Emit>
    void stripes(std::size_t f, Emit& emit) {
        const Fruit& x = s_.fruits[f];
        const double v = p_.voxel, r = x.radius, at = dot(x.centre, across_);
        const double L = x.reach(across_);
        Vec3 w = across_, e1 = toward_scanner_, e2{0, 0, 1};
        if (!x.round()) {  // A across = L w: A is symmetric, so |A across| is the support width
            const Vec3 stretched = sub(x.at(across_, r), x.centre);
            w = unit(stretched);
            e1 = unit(sub(toward_scanner_, scaled(w, dot(toward_scanner_, w))));
            e2 = cross(w, e1);
        }
        // points along a line: its circle's circumference at most this many times the circle's
        const double widest = x.largest() / L;
        for (auto k = static_cast<std::int64_t>(std::ceil((at - L) / v));
             static_cast<double>(k) * v <= at + L; ++k) {
            const double t = static_cast<double>(k) * v - at;
            const double rho = std::sqrt(std::max(0.0, L * L - t * t));
            const auto n = static_cast<std::int64_t>(std::ceil(2 * kPi * rho * widest / (v / 3)));
            const double phase = rng_.uniform(0, 2 * kPi);
            for (std::int64_t j = 0; j < n; ++j) {
                const double phi =
                    phase + 2 * kPi * static_cast<double>(j) / static_cast<double>(n);
                Vec3 d;
                for (int a = 0; a < 3; ++a) {
                    d[a] = (t * w[a] + rho * (std::cos(phi) * e1[a] + std::sin(phi) * e2[a])) / L;
                }
                if (dot(x.normal(d), toward_scanner_) > 0) {
                    emit(d, r, 1);
                }
            }
        }
    }

    const Scene& s_;
    const RenderParams& p_;
    Rng& rng_;
    Painter paint_;
    Rendered& out_;
    std::vector<std::vector<std::uint32_t>> members_;
    Vec3 toward_scanner_{}, across_{};
};

}  // namespace

Rendered render_sampled(const Scene& s, const RenderParams& p) {
    for (const auto& f : s.fruits) {
        if (f.smallest() < p.voxel) {
            throw InvalidArgument(
                "render: the point spacing must not be larger than the smallest fruit radius");
        }
    }
    Rendered out;
    Rng rng(p.seed, 3);
    Sampler sampler(s, p, rng, out);
    for (std::size_t f = 0; f < s.fruits.size(); ++f) {
        sampler.fruit(f);
    }
    const std::size_t fruit_total = out.xyz.size();
    sampler.leaves();
    add_ground_and_outliers(s, p, fruit_total, rng, out);
    add_wood(s, p, out);
    return shuffled_points(out, s.fruits.size(), rng);
}

}  // namespace pc::scenes::detail
