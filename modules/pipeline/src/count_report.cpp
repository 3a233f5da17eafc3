#include <pc/core/stats.h>
#include <pc/pipeline/count_report.h>

namespace pc::pipeline {

using nlohmann::ordered_json;

nlohmann::ordered_json count_report(const segmentation::ClusterSummary& s,
                                    std::optional<double> gt,
                                    const std::vector<StepRecord>& steps,
                                    const std::vector<std::string>& warnings,
                                    const std::optional<EpsCheck>& eps_check) {
    ordered_json j;
    j["count"] = s.clusters.size();
    if (gt) {
        j["gt"] = *gt;
        j["count_error"] = static_cast<double>(s.clusters.size()) - *gt;
        j["recovery"] = *gt > 0 ? ordered_json(static_cast<double>(s.clusters.size()) / *gt)
                                : ordered_json(nullptr);
    }
    j["noise_points"] = s.noise_points;
    j["small_clusters"] = s.small_clusters;
    ordered_json cl = ordered_json::array();
    for (const auto& c : s.clusters) {
        cl.push_back({{"id", c.id},
                      {"points", c.points},
                      {"centroid", c.centroid},
                      {"aabb", {{"min", c.min}, {"max", c.max}}}});
    }
    j["clusters"] = cl;
    std::vector<double> sizes;
    for (const auto& c : s.clusters) {
        sizes.push_back(static_cast<double>(c.points));
    }
    const double med = sizes.empty() ? 0.0 : median(sizes);
    std::size_t several = 0, fragments = 0;
    for (const auto& c : s.clusters) {
        several += static_cast<double>(c.points) > 1.75 * med;
        fragments += static_cast<double>(c.points) < 0.25 * med;
    }
    j["cluster_sizes"] = {{"median", med}, {"several", several}, {"fragments", fragments}};
    if (!steps.empty()) {
        ordered_json st = ordered_json::array();
        for (const auto& r : steps) {
            ordered_json step{
                {"step", r.name}, {"points_in", r.points_in}, {"points_out", r.points_out}};
            for (const auto& [key, value] : r.values) {
                step[key] = value;
            }
            if (!r.rule.empty()) {
                step["rule"] = r.rule;
            }
            st.push_back(step);
        }
        j["steps"] = st;
    }
    if (eps_check) {
        j["eps_check"] = {{"eps", eps_check->eps}, {"counts", eps_check->counts}};
    }
    j["warnings"] = warnings;
    return j;
}

}  // namespace pc::pipeline
