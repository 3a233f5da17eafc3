// pc_fruitcount: the whole counting chain in one process (colour filter, crop, voxel, kNN outlier,
// DBSCAN, recursive split, count), with the same labels as the piped chain.
#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/pipeline/steps.h>

#include "color_options.h"
#include "split_options.h"

namespace pl = pc::pipeline;
namespace seg = pc::segmentation;

int main(int argc, char** argv) {
    // Each step's Params live here, bound to options; the preset fills them first.
    pl::ChainParams chain = pl::preset("dense");
    pc::tools::ColorOptions color;
    color.from_preset(chain);
    pc::filters::CropParams crop;
    pc::filters::VoxelParams voxel;
    pc::filters::KnnOutlierParams knn = *chain.knn;
    seg::RecursiveSplitParams split = *chain.split;
    bool no_color = false, no_knn = false, no_split = false;
    std::optional<double> gt;
    bool plain = false, eps_check = false;
    std::string cloud_out;

    pc::cli::Tool tool("pc_fruitcount",
                       "count fruit: colour filter, crop, voxel, kNN outlier, DBSCAN, recursive "
                       "split and count in one process (default preset: dense)",
                       pc::cli::Output::kText);
    tool.presets(pl::preset_names(), [&](const std::string& name) {
        chain = pl::preset(name);
        color.from_preset(chain);
        crop = chain.crop.value_or(crop);
        voxel = chain.voxel.value_or(voxel);
        knn = chain.knn.value_or(knn);
        split = chain.split.value_or(split);
    });
    pc::tools::bind_color_options(tool, color, "colour: ");
    tool.flag("no-color", &no_color, "skip the colour filter");
    tool.option(
        "crop-min", "off",
        [&](const std::string& s) {
            crop.min = pc::cli::parse_triple("crop-min", s);
            chain.crop = crop;
        },
        "crop: lower corner x,y,z, included (enables the crop step)");
    tool.option(
        "crop-max", "off",
        [&](const std::string& s) {
            crop.max = pc::cli::parse_triple("crop-max", s);
            chain.crop = crop;
        },
        "crop: upper corner x,y,z, included (enables the crop step)");
    tool.option(
        "leaf", "off",
        [&](const std::string& s) {
            voxel.leaf = pc::cli::parse_double("leaf", s);
            chain.voxel = voxel;
        },
        "voxel: leaf size (enables the voxel step)");
    tool.option("k", &knn.k, "kNN outlier: neighbours, the point itself NOT counted");
    tool.option("drop-percentile", &knn.drop_percentile,
                "kNN outlier: drop mean distance >= P(100-P)");
    tool.option("std-mul", &knn.std_mul,
                "kNN outlier: instead drop mean distance > mean + M sigma");
    tool.flag("no-knn", &no_knn, "skip the kNN outlier filter");
    tool.option(
        "eps", pl::eps_text(chain.dbscan, chain.eps),
        [&](const std::string& s) { pl::parse_eps(s, chain.dbscan, chain.eps); },
        "DBSCAN: neighbour iff distance <= eps; 'auto' (4 x the point spacing), 'Nxs' (N x it), "
        "'knee' (k-distance knee)");
    tool.option("min-points", &chain.dbscan.min_points,
                "DBSCAN: core needs this many, itself included");
    pc::tools::bind_split_options(tool, split, "split: ");
    tool.flag("no-split", &no_split, "skip the recursive split");
    tool.option("count-min-points", &chain.count_min_points,
                "count clusters with at least this many points");
    tool.flag("eps-check", &eps_check,
              "count again at 0.8 and 1.25 x the eps used (DBSCAN and split rerun): a count that "
              "swings by more than 2x is a warning; eps and counts go to the report");
    tool.option("gt", &gt, "ground-truth count: adds error and recovery to the report");
    tool.flag("plain", &plain, "print only the count");
    tool.option("cloud", &cloud_out, "also write the labelled cloud (binary PCD) to this file");
    tool.epilog("\nSee docs/tools/pc_fruitcount.md for the presets and the steps.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        color.apply(chain);
        if (no_color) {
            chain.color.reset();
            chain.fruit_color.reset();
        }
        chain.knn = no_knn ? std::nullopt : std::optional(knn);
        chain.split = no_split ? std::nullopt : std::optional(split);
        if (chain.crop) {
            chain.crop = crop;
        }
        if (chain.voxel) {
            chain.voxel = voxel;
        }
        pc::io::Blob in = io.read();
        const std::size_t points = in.size();
        const pl::ChainResult r =
            pl::run_chain(std::move(in), chain, [&](const std::string& n) { io.note(n); });
        const auto summary = pl::summarize(r.labelled, chain.count_min_points);
        std::vector<std::string> warnings = r.warnings;
        for (const auto& w : pl::count_warnings(summary, points)) {
            warnings.push_back(w);
        }
        std::optional<pl::EpsCheck> check;
        if (eps_check) {
            check = pl::check_eps(r, chain);
            if (check->warning) {
                warnings.push_back(*check->warning);
            }
        }
        for (const auto& w : warnings) {
            io.warn(w);
        }
        if (!cloud_out.empty()) {
            pc::cli::write_cloud_file(cloud_out, r.labelled);
        }
        io.write_text(plain ? std::to_string(summary.clusters.size()) + "\n"
                            : pl::count_report(summary, gt, r.steps, warnings, check));
    });
}
