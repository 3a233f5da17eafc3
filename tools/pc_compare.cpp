// pc_compare: cloud-to-cloud distances, accuracy/completeness/F-score at tau, interior coverage.
#include <cmath>
#include <sstream>

#include <pc/cli/report.h>
#include <pc/core/error.h>
#include <pc/features/compare.h>
#include <pc/io/points.h>

namespace pf = pc::features;

namespace {

nlohmann::ordered_json stats_json(const pf::DirectionStats& s) {
    return {{"points", s.points},
            {"mean", pc::cli::json_number(s.mean)},
            {"median", pc::cli::json_number(s.median)},
            {"rms", pc::cli::json_number(s.rms)},
            {"max", pc::cli::json_number(s.max)},
            {"within_tau", s.within_tau}};
}

std::string cell(double v) { return std::isfinite(v) ? pc::format_number(v) : ""; }

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> inputs;
    pf::CompareParams p;
    bool csv = false, markdown = false;
    pc::cli::Tool tool("pc_compare",
                       "compare cloud A (reconstruction) with B (reference): distances both ways, "
                       "accuracy, completeness, F-score at tau, interior coverage",
                       pc::cli::Output::kText);
    tool.inputs(&inputs,
                "A B: the reconstruction, then the reference (A from -i or stdin if only "
                "B is given)",
                2);
    tool.option("tau", &p.tau,
                "distance threshold: a point counts if its nearest neighbour is <= tau");
    tool.option("voxel", &p.voxel,
                "voxel side for interior coverage (grid anchored at the origin)");
    tool.flag("csv", &csv, "one CSV row instead of JSON");
    tool.flag("markdown", &markdown, "a markdown table instead of JSON");
    tool.epilog("\nDefinitions in docs/tools/pc_compare.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (inputs.size() != 2) {
            throw pc::InvalidArgument("expected two inputs A B, got " +
                                      std::to_string(inputs.size()));
        }
        if (csv && markdown) {
            throw pc::InvalidArgument("--csv and --markdown exclude each other");
        }
        p.validate();
        const pc::Cloud a = pc::io::xyz(io.read(inputs[0]));
        const pc::Cloud b = pc::io::xyz(io.read(inputs[1]));
        io.note("comparing: nearest neighbours both ways, then voxel coverage");
        const pf::CompareResult r =
            pf::compare(a, b, p, [&](const std::string& what) { io.note(what); });
        const std::vector<std::string> warnings = pf::compare_warnings(r, p);
        for (const auto& w : warnings) {
            io.warn(w);
        }
        std::ostringstream out;
        if (csv) {
            out << "a,b,tau,voxel,a_points,b_points,a_to_b_mean,a_to_b_median,a_to_b_rms,a_to_b_"
                   "max,"
                   "b_to_a_mean,b_to_a_median,b_to_a_rms,b_to_a_max,chamfer,precision,recall,"
                   "fscore,"
                   "interior_coverage\n";
            out << pc::io::display_name(inputs[0]) << ',' << pc::io::display_name(inputs[1]);
            for (double v : {p.tau, p.voxel, double(r.a_to_b.points), double(r.b_to_a.points),
                             r.a_to_b.mean, r.a_to_b.median, r.a_to_b.rms, r.a_to_b.max,
                             r.b_to_a.mean, r.b_to_a.median, r.b_to_a.rms, r.b_to_a.max, r.chamfer,
                             r.precision, r.recall, r.fscore, r.interior_coverage}) {
                out << ',' << cell(v);
            }
            out << '\n';
        } else if (markdown) {
            out << "| metric | value |\n| --- | ---: |\n";
            const std::pair<const char*, double> rows[] = {
                {"A→B mean distance", r.a_to_b.mean},
                {"B→A mean distance", r.b_to_a.mean},
                {"chamfer", r.chamfer},
                {"accuracy (precision)", r.precision},
                {"completeness (recall)", r.recall},
                {"F-score", r.fscore},
                {"interior coverage", r.interior_coverage}};
            for (const auto& [name, v] : rows) {
                char buf[32];
                std::snprintf(buf, sizeof buf, "%.6g", v);
                out << "| " << name << " | " << buf << " |\n";
            }
        } else {
            nlohmann::ordered_json j{{"a", pc::io::display_name(inputs[0])},
                                     {"b", pc::io::display_name(inputs[1])}};
            j.update(pc::cli::report_header(io));
            j["tau"] = p.tau;
            j["voxel"] = p.voxel;
            j["a_to_b"] = stats_json(r.a_to_b);
            j["b_to_a"] = stats_json(r.b_to_a);
            j["chamfer"] = r.chamfer;
            j["precision"] = r.precision;
            j["recall"] = r.recall;
            j["fscore"] = r.fscore;
            j["interior_coverage"] = {{"b_voxels", r.b_voxels},
                                      {"shared_voxels", r.shared_voxels},
                                      {"fraction", r.interior_coverage}};
            j["box_overlap"] = r.box_overlap;
            j["warnings"] = warnings;
            out << j.dump(1) << '\n';
        }
        io.write_text(out.str());
    });
}
