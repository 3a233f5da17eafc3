// The PCL side of bench/run.sh: one operation per run, timed inside the process (file reading
// excluded unless the operation is the reading), result summary on stdout as "seconds value".
//   pcl_peer read FILE                      loadPCDFile (PointXYZ)
//   pcl_peer write FILE OUT                 savePCDFileBinary
//   pcl_peer ece FILE TOLERANCE MIN_SIZE    EuclideanClusterExtraction -> clusters
//   pcl_peer sor FILE K STD                 StatisticalOutlierRemoval -> points kept
//   pcl_peer knn FILE K THREADS             mean distance to the K nearest (KdTreeFLANN, OpenMP)
//   pcl_peer hull FILE                      ConvexHull (qhull) -> volume
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <omp.h>

#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/io/pcd_io.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/surface/convex_hull.h>

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using Clock = std::chrono::steady_clock;

namespace {

double since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

Cloud::Ptr load(const char* path) {
    Cloud::Ptr c(new Cloud);
    if (pcl::io::loadPCDFile(path, *c) != 0) {
        std::fprintf(stderr, "pcl_peer: cannot read %s\n", path);
        std::exit(1);
    }
    return c;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: pcl_peer read|write|ece|sor|knn|hull FILE [args]\n");
        return 2;
    }
    const std::string op = argv[1];
    if (op == "read") {
        const auto t = Clock::now();
        const auto c = load(argv[2]);
        std::printf("%.6f %zu\n", since(t), c->size());
        return 0;
    }
    const auto c = load(argv[2]);
    const auto t = Clock::now();
    if (op == "write" && argc == 4) {
        pcl::io::savePCDFileBinary(argv[3], *c);
        std::printf("%.6f %zu\n", since(t), c->size());
    } else if (op == "ece" && argc == 5) {
        pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
        tree->setInputCloud(c);
        std::vector<pcl::PointIndices> clusters;
        pcl::EuclideanClusterExtraction<pcl::PointXYZ> ece;
        ece.setClusterTolerance(std::atof(argv[3]));
        ece.setMinClusterSize(std::atoi(argv[4]));
        ece.setMaxClusterSize(static_cast<int>(c->size()));
        ece.setSearchMethod(tree);
        ece.setInputCloud(c);
        ece.extract(clusters);
        std::printf("%.6f %zu\n", since(t), clusters.size());
    } else if (op == "sor" && argc == 5) {
        Cloud out;
        pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
        sor.setInputCloud(c);
        sor.setMeanK(std::atoi(argv[3]));
        sor.setStddevMulThresh(std::atof(argv[4]));
        sor.filter(out);
        std::printf("%.6f %zu\n", since(t), out.size());
    } else if (op == "knn" && argc == 5) {
        const int k = std::atoi(argv[3]);
        omp_set_num_threads(std::atoi(argv[4]));
        pcl::KdTreeFLANN<pcl::PointXYZ> tree;
        tree.setInputCloud(c);
        std::vector<float> mean(c->size());
#pragma omp parallel
        {
            std::vector<int> idx(k + 1);
            std::vector<float> d2(k + 1);
#pragma omp for schedule(static)
            for (std::int64_t i = 0; i < static_cast<std::int64_t>(c->size()); ++i) {
                const int found =
                    tree.nearestKSearch((*c)[i], k + 1, idx, d2);  // includes the point
                double s = 0;
                for (int j = 1; j < found; ++j) {
                    s += std::sqrt(d2[j]);
                }
                mean[i] = static_cast<float>(s / std::max(1, found - 1));
            }
        }
        double total = 0;
        for (float m : mean) {
            total += m;
        }
        std::printf("%.6f %.9g\n", since(t), total / static_cast<double>(c->size()));
    } else if (op == "hull") {
        Cloud out;
        pcl::ConvexHull<pcl::PointXYZ> hull;
        hull.setInputCloud(c);
        hull.setComputeAreaVolume(true);
        hull.reconstruct(out);
        std::printf("%.6f %.9g\n", since(t), hull.getTotalVolume());
    } else {
        std::fprintf(stderr, "pcl_peer: bad arguments for %s\n", op.c_str());
        return 2;
    }
    return 0;
}
