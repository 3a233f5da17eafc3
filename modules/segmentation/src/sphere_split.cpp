#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include <pc/core/random.h>
#include <pc/segmentation/sphere_split.h>

namespace pc::segmentation {

namespace {

Eigen::Vector3d at(const XyzView& cloud, std::uint32_t i) {
    const pcl::PointXYZ p = cloud[i];
    return {p.x, p.y, p.z};
}

Sphere solve(const Eigen::Matrix4d& ata, const Eigen::Vector4d& atb) {
    Sphere s;
    const Eigen::FullPivLU<Eigen::Matrix4d> lu(ata);
    if (!lu.isInvertible()) {
        return s;
    }
    const Eigen::Vector4d x = lu.solve(atb);  // c (3), d = r² − ‖c‖²
    const Eigen::Vector3d c = x.head<3>();
    const double r2 = x[3] + c.squaredNorm();
    if (!(r2 > 0) || !std::isfinite(r2)) {
        return s;
    }
    s.centre = {c.x(), c.y(), c.z()};
    s.radius = std::sqrt(r2);
    s.ok = true;
    return s;
}

double surface_distance(const Sphere& s, const Eigen::Vector3d& p) {
    return std::abs((p - Eigen::Vector3d(s.centre[0], s.centre[1], s.centre[2])).norm() - s.radius);
}

}  // namespace

Sphere fit_sphere(const XyzView& cloud, std::span<const std::uint32_t> members) {
    if (members.size() < 4) {
        return {};
    }
    // Centred coordinates keep the normal equations well conditioned.
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (auto i : members) {
        mean += at(cloud, i);
    }
    mean /= static_cast<double>(members.size());
    Eigen::Matrix4d ata = Eigen::Matrix4d::Zero();
    Eigen::Vector4d atb = Eigen::Vector4d::Zero();
    for (auto i : members) {
        const Eigen::Vector3d p = at(cloud, i) - mean;
        const Eigen::Vector4d row(2 * p.x(), 2 * p.y(), 2 * p.z(), 1.0);
        ata += row * row.transpose();
        atb += row * p.squaredNorm();
    }
    Sphere s = solve(ata, atb);
    if (!s.ok) {
        return s;
    }
    for (int a = 0; a < 3; ++a) {
        s.centre[a] += mean[a];
    }
    double sum = 0;
    for (auto i : members) {
        const double d = surface_distance(s, at(cloud, i));
        sum += d * d;
    }
    s.rms = std::sqrt(sum / static_cast<double>(members.size()));
    return s;
}

std::vector<std::uint32_t> split_hollow(const XyzView& cloud,
                                        std::span<const std::uint32_t> members,
                                        double fruit_radius,
                                        double spacing,
                                        double typical_points,
                                        const HollowSplitParams& p) {
    std::vector<std::uint32_t> part(members.size(), 0);
    const double band = std::max(p.band * fruit_radius, 1.5 * spacing);
    const auto need = static_cast<std::size_t>(std::max(8.0, p.min_inliers * typical_points));
    const double lo = p.radius_low * fruit_radius, hi = p.radius_high * fruit_radius;
    const double reach2 =
        (1.2 * fruit_radius) * (1.2 * fruit_radius);  // samples from one fruit, mostly
    if (members.size() < 2 * need) {
        return part;
    }
    std::vector<Eigen::Vector3d> pos(members.size());
    for (std::size_t k = 0; k < members.size(); ++k) {
        pos[k] = at(cloud, members[k]);
    }
    Rng rng(p.seed ^ (0x9E3779B97F4A7C15ull * (members.front() + 1)));
    std::vector<std::size_t> left(members.size());
    for (std::size_t k = 0; k < left.size(); ++k) {
        left[k] = k;
    }
    std::vector<Sphere> spheres;
    std::vector<std::size_t> near, inliers, probe;
    while (left.size() >= need) {
        // Candidates are scored on at most 1000 of the remaining points (a fixed stride).
        probe.clear();
        const std::size_t stride = std::max<std::size_t>(1, left.size() / 1000);
        for (std::size_t q = 0; q < left.size(); q += stride) {
            probe.push_back(left[q]);
        }
        Sphere best;
        std::size_t best_score = 0;
        for (std::uint32_t it = 0; it < p.iterations; ++it) {
            const Eigen::Vector3d& seed = pos[left[rng.below(left.size())]];
            near.clear();
            for (auto k : left) {
                if ((pos[k] - seed).squaredNorm() <= reach2) {
                    near.push_back(k);
                }
            }
            if (near.size() < 4) {
                continue;
            }
            Eigen::Matrix4d ata = Eigen::Matrix4d::Zero();
            Eigen::Vector4d atb = Eigen::Vector4d::Zero();
            for (int q = 0; q < 4; ++q) {
                const Eigen::Vector3d x = pos[near[rng.below(near.size())]] - seed;
                const Eigen::Vector4d row(2 * x.x(), 2 * x.y(), 2 * x.z(), 1.0);
                ata += row * row.transpose();
                atb += row * x.squaredNorm();
            }
            Sphere s = solve(ata, atb);
            if (!s.ok || s.radius < lo || s.radius > hi) {
                continue;
            }
            for (int a = 0; a < 3; ++a) {
                s.centre[a] += seed[a];
            }
            std::size_t score = 0;
            for (auto k : probe) {
                score += surface_distance(s, pos[k]) <= band;
            }
            if (score > best_score) {
                best_score = score;
                best = s;
            }
        }
        if (best_score * stride < need) {
            break;
        }
        // Refit on the inliers; keep the refit only if it stays a fruit-sized sphere.
        const auto collect = [&](const Sphere& s) {
            inliers.clear();
            for (auto k : left) {
                if (surface_distance(s, pos[k]) <= band) {
                    inliers.push_back(k);
                }
            }
        };
        collect(best);
        std::vector<std::uint32_t> ids;
        for (auto k : inliers) {
            ids.push_back(members[k]);
        }
        const Sphere refit = fit_sphere(cloud, ids);
        if (refit.ok && refit.radius >= lo && refit.radius <= hi) {
            best = refit;
            collect(best);
        }
        if (inliers.size() < need) {
            break;
        }
        spheres.push_back(best);
        std::vector<std::uint8_t> taken(members.size(), 0);
        for (auto k : inliers) {
            taken[k] = 1;
        }
        std::erase_if(left, [&](std::size_t k) { return taken[k] != 0; });
    }
    // Spheres whose centres are closer than one fruit radius describe the same fruit (two caps).
    std::vector<std::uint32_t> group(spheres.size());
    std::uint32_t groups = 0;
    for (std::size_t a = 0; a < spheres.size(); ++a) {
        group[a] = groups;
        for (std::size_t b = 0; b < a; ++b) {
            const auto& x = spheres[a].centre;
            const auto& y = spheres[b].centre;
            const double d2 = (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                              (x[2] - y[2]) * (x[2] - y[2]);
            if (d2 < fruit_radius * fruit_radius) {
                group[a] = group[b];
                break;
            }
        }
        groups += group[a] == groups;
    }
    if (groups < 2) {
        return part;
    }
    for (std::size_t k = 0; k < members.size(); ++k) {
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t s = 0; s < spheres.size(); ++s) {
            const double d = surface_distance(spheres[s], pos[k]);
            if (d < best) {
                best = d;
                part[k] = group[s];
            }
        }
    }
    return part;
}

}  // namespace pc::segmentation
