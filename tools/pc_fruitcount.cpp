// pc_fruitcount: the whole counting chain in one process (colour filter, crop, voxel, kNN outlier,
// DBSCAN, recursive split, count), with the same labels as the piped chain.
#include <cmath>
#include <filesystem>

#include <pc/cli/report.h>
#include <pc/core/error.h>
#include <pc/pipeline/count_report.h>

#include "color_options.h"
#include "count_plot.h"
#include "plots.h"
#include "split_options.h"
#include "stem.h"

namespace pl = pc::pipeline;
namespace seg = pc::segmentation;

namespace {

std::string triple_text(const std::array<double, 3>& v) {
    return pc::format_number(v[0]) + "," + pc::format_number(v[1]) + "," + pc::format_number(v[2]);
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> inputs;
    // Each step's Params live here, bound to options; the preset fills them first.
    pl::ChainParams chain = pl::preset("dense");
    pc::tools::ColorOptions color;
    color.from_preset(chain);
    pc::filters::CropParams crop;
    pc::filters::VoxelParams voxel;
    // The kNN step runs when the preset has it (the paper's do, dense does not) or one of its
    // options is given (as --leaf enables voxel); its parameters start as the paper's.
    pc::filters::KnnOutlierParams knn = pl::preset("paper-dense").knn.value();
    seg::RecursiveSplitParams split = *chain.split;
    bool no_color = false, no_knn = false, no_split = false, no_wood = false;
    std::optional<double> gt;
    bool eps_check = false;
    bool no_eps_check = false;
    std::string cloud_out, cloud_all, plot;

    pc::cli::Tool tool("pc_fruitcount",
                       "count fruit: colour filter, crop, voxel, kNN outlier, DBSCAN, recursive "
                       "split and count in one process (default preset: dense)",
                       pc::cli::Output::kText);
    tool.inputs(&inputs, "clouds, one report each ('-' = stdin, the default)");
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
    tool.option("judge-points", &chain.judge_points,
                "colour: natural colours on a cloud of more points: the colour classes that "
                "compete are judged on every k-th point (at most this many; faster, but the "
                "choice may differ), the class kept is counted on all; 0: judged on all");
    tool.option(
        "crop-min", "off",
        [&](const std::string& s) {
            crop.min = pc::cli::parse_triple("crop-min", s);
            chain.crop = crop;
        },
        "crop: lower corner x,y,z, included (enables the crop step)",
        [&] { return chain.crop ? triple_text(chain.crop->min) : std::string("off"); });
    tool.option(
        "crop-max", "off",
        [&](const std::string& s) {
            crop.max = pc::cli::parse_triple("crop-max", s);
            chain.crop = crop;
        },
        "crop: upper corner x,y,z, included (enables the crop step)",
        [&] { return chain.crop ? triple_text(chain.crop->max) : std::string("off"); });
    tool.option(
        "leaf", "off",
        [&](const std::string& s) {
            voxel.leaf = pc::cli::parse_double("leaf", s);
            chain.voxel = voxel;
        },
        "voxel: leaf size (enables the voxel step)",
        [&] { return chain.voxel ? pc::format_number(chain.voxel->leaf) : std::string("off"); });
    tool.option(
        "k", std::to_string(knn.k),
        [&](const std::string& s) {
            const double k = pc::cli::parse_double("k", s);
            if (!(k >= 1 && k <= 1e6 && k == std::floor(k))) {
                throw pc::InvalidArgument("--k: a whole number of neighbours >= 1, got '" + s +
                                          "'");
            }
            knn.k = static_cast<std::uint32_t>(k);
            chain.knn = knn;
        },
        "kNN outlier: neighbours, the point itself NOT counted (enables the step; the paper "
        "presets run it)",
        [&] { return std::to_string(knn.k); });
    tool.option(
        "drop-percentile", pc::format_number(knn.drop_percentile),
        [&](const std::string& s) {
            knn.drop_percentile = pc::cli::parse_double("drop-percentile", s);
            chain.knn = knn;
        },
        "kNN outlier: drop mean distance >= P(100-P) (enables the step)",
        [&] { return pc::format_number(knn.drop_percentile); });
    tool.option(
        "std-mul", "off",
        [&](const std::string& s) {
            knn.std_mul = pc::cli::parse_double("std-mul", s);
            chain.knn = knn;
        },
        "kNN outlier: instead drop mean distance > mean + M sigma (enables the step)",
        [&] { return knn.std_mul ? pc::format_number(*knn.std_mul) : std::string("off"); });
    tool.flag("no-knn", &no_knn, "skip the kNN outlier filter (of a paper preset)");
    tool.option(
        "eps", pl::eps_text(chain.dbscan, chain.eps),
        [&](const std::string& s) { pl::parse_eps(s, chain.dbscan, chain.eps); },
        "DBSCAN: neighbour iff distance <= eps; 'auto' (4 x the point spacing), 'Nxs' (N x it), "
        "'knee' (k-distance knee)",
        [&] { return pl::eps_text(chain.dbscan, chain.eps); });
    tool.option("min-points", &chain.dbscan.min_points,
                "DBSCAN: core needs this many, itself included");
    pc::tools::bind_split_options(tool, split, "split: ");
    tool.flag("no-split", &no_split, "skip the recursive split");
    tool.flag("no-wood", &no_wood,
              "keep the parts coloured like the wood (one part far too large for a fruit, "
              "coloured unlike the others, and the parts nearer its colour than theirs)");
    tool.option("count-min-points", &chain.count_min_points,
                "count clusters with at least this many points");
    tool.flag("eps-check", &eps_check,
              "count again at 0.8 and 1.25 x the eps used (DBSCAN and split rerun): a count that "
              "swings by more than 2x is a warning; eps and counts go to the report. Without it, "
              "run only when the spheres split's centres took under 90 % of the points");
    tool.flag("no-eps-check", &no_eps_check, "never run the eps check");
    tool.option("gt", &gt, "ground-truth count: adds error and recovery to the report");
    const pc::cli::Report report(tool, "count");
    tool.option("cloud", &cloud_out,
                "also write the labelled cloud to this file (binary PCD, or binary PLY for a .ply "
                "name); {stem} becomes the input's name without extension (needed for several "
                "inputs)");
    tool.option("plot", &plot,
                "also draw the cluster sizes and radii as histograms into this PNG (its numbers "
                "beside it as .csv); {stem} as for --cloud");
    tool.option("cloud-all", &cloud_all,
                "also write the whole input with the chain's label on every point (0: removed by "
                "a step, or noise), every field kept; {stem} as for --cloud");
    tool.epilog("\nSee docs/tools/pc_fruitcount.md for the presets and the steps.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        color.apply(chain);
        if (no_color) {
            chain.color.reset();
            chain.fruit_color.reset();
        }
        if (no_color || no_wood) {
            chain.wood.reset();
        }
        if (chain.knn) {
            chain.knn = knn;
        }
        if (no_knn) {
            chain.knn.reset();
        }
        chain.split = no_split ? std::nullopt : std::optional(split);
        if (chain.crop) {
            chain.crop = crop;
        }
        if (chain.voxel) {
            chain.voxel = voxel;
        }
        for (const auto& [option, path] :
             {std::pair{"cloud", &cloud_out}, std::pair{"cloud-all", &cloud_all}}) {
            pc::tools::check_stem(option, *path, inputs.size());
            if (!path->empty()) {
                (void)pc::cli::container_for(*path);  // a .las name refused before any work
            }
        }
        if (eps_check && no_eps_check) {
            throw pc::InvalidArgument("--eps-check and --no-eps-check: give one of them");
        }
        pc::tools::check_plot_path(plot);
        pc::tools::check_stem("plot", plot, inputs.size());
        if (!cloud_all.empty() && chain.voxel) {
            throw pc::InvalidArgument(
                "--cloud-all: the whole cloud cannot be labelled after a "
                "voxel step (its points are voxel centroids): drop --leaf");
        }
        report.each(io, inputs, [&](const std::string& path) {
            pc::io::Blob in = io.read(path);
            const std::size_t points = in.size();
            const auto progress = [&](const std::string& n) { io.note(n); };
            pl::MarkedChain marked;
            if (cloud_all.empty()) {
                marked.chain = pl::run_chain(std::move(in), chain, progress);
            } else {
                marked = pl::run_chain_marked(std::move(in), chain, progress);
                pc::cli::write_cloud_file(pc::tools::with_stem(cloud_all, path), marked.marked);
            }
            const pl::ChainResult& r = marked.chain;
            const auto summary = pl::summarize(r.labelled, chain.count_min_points);
            std::vector<std::string> warnings = r.warnings;
            for (const auto& w : pl::count_warnings(summary, points)) {
                warnings.push_back(w);
            }
            std::optional<pl::EpsCheck> check;
            if (eps_check || (!no_eps_check && pl::eps_sensitive(r))) {
                check = pl::check_eps(r, chain);
                if (check->warning) {
                    warnings.push_back(*check->warning);
                }
            }
            if (!cloud_out.empty()) {
                pc::cli::write_cloud_file(pc::tools::with_stem(cloud_out, path), r.labelled);
            }
            if (!plot.empty()) {
                pc::tools::write_plot(pc::tools::with_stem(plot, path),
                                      pc::tools::count_panels(summary));
            }
            return pl::count_report(summary, gt, r.steps, warnings, check);
        });
    });
}
