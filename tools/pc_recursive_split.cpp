// pc_recursive_split: split over-merged clusters by k-means (k = 2) until none violates the rule.
#include <pc/cli/tool.h>
#include <pc/pipeline/steps.h>

namespace pl = pc::pipeline;
namespace seg = pc::segmentation;

int main(int argc, char** argv) {
    seg::RecursiveSplitParams p;
    pc::cli::Tool tool("pc_recursive_split",
                       "split clusters in `label` whose size and AABB volume exceed median-based "
                       "thresholds; relabel 1..N");
    tool.option(
        "rule", seg::split_rule_name(p.rule),
        [&](const std::string& s) { p.rule = seg::parse_split_rule(s); },
        "paper: medians over all clusters; script: size median over clusters with more "
        "than --median-min-points, volume median over clusters within --size-band of it; "
        "cores: cut each cluster at the necks between its solid cores (no medians, no k-means)");
    tool.option("core-fraction", &p.core_fraction,
                "cores rule: core depth as a fraction of the estimated fruit radius");
    tool.option("min-relative-size", &p.min_relative_size,
                "cores rule: clusters below this x the median cluster size become noise");
    tool.option("size-factor", &p.size_factor, "split needs points > this x median size");
    tool.option("volume-factor", &p.volume_factor, "and AABB volume > this x median volume");
    tool.option("median-min-points", &p.median_min_points,
                "script rule: size median over clusters with more points than this");
    tool.option("size-band", &p.size_band,
                "script rule: volume median over clusters with |size - median| <= band x median");
    tool.option("min-cluster-size", &p.min_cluster_size,
                "final clusters with fewer points become noise (label 0)");
    tool.option("restarts", &p.restarts, "k-means++ restarts per split");
    tool.option("seed", &p.seed, "k-means seed");
    tool.presets(pl::preset_names(), [&](const std::string& name) { p = *pl::preset(name).split; });
    tool.epilog(
        "\nThresholds are fixed from the input clusters. See docs/tools/pc_recursive_split.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pl::Step s = pl::apply_recursive_split(io.read(), p);
        io.note(s.note);
        for (const auto& w : s.warnings) {
            io.warn(w);
        }
        io.write(s.blob);
    });
}
