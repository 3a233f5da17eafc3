// Our reader against PCL's own writer and loader, and PCL's loader against our writer.
#include <random>

#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <pc/io/pcd.h>
#include <pc/io/read.h>

#include "support/run_tool.h"

namespace pc::io {
namespace {

pcl::PointCloud<pcl::PointXYZRGBNormal> typed_cloud() {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-3, 3);
    pcl::PointCloud<pcl::PointXYZRGBNormal> c;
    for (int i = 0; i < 500; ++i) {
        pcl::PointXYZRGBNormal p;
        p.x = u(rng);
        p.y = u(rng);
        p.z = i == 7 ? std::numeric_limits<float>::quiet_NaN() : u(rng);
        p.rgba = static_cast<std::uint32_t>(rng());
        p.normal_x = u(rng);
        p.normal_y = u(rng);
        p.normal_z = u(rng);
        p.curvature = u(rng);
        c.push_back(p);
    }
    c.is_dense = false;
    return c;
}

/// Field-by-field comparison of two blobs (padding ignored; rgb may be F or U).
void expect_same_fields(const pcl::PCLPointCloud2& ours, const pcl::PCLPointCloud2& pcls) {
    ASSERT_EQ(ours.width, pcls.width);
    ASSERT_EQ(ours.height, pcls.height);
    const std::size_t n = std::size_t{ours.width} * ours.height;
    for (const auto& pf : pcls.fields) {
        if (pf.name == "_") {
            continue;
        }
        const auto it = std::find_if(ours.fields.begin(), ours.fields.end(),
                                     [&](const auto& f) { return f.name == pf.name; });
        ASSERT_NE(it, ours.fields.end()) << pf.name;
        EXPECT_EQ(it->count, pf.count) << pf.name;
        EXPECT_EQ(type_size(it->datatype), type_size(pf.datatype)) << pf.name;
        if (pf.name != "rgb" && pf.name != "rgba") {
            EXPECT_EQ(it->datatype, pf.datatype) << pf.name;
        }
        const std::size_t fs = type_size(pf.datatype) * pf.count;
        for (std::size_t i = 0; i < n; ++i) {
            ASSERT_EQ(0, std::memcmp(&ours.data[i * ours.point_step + it->offset],
                                     &pcls.data[i * pcls.point_step + pf.offset], fs))
                << pf.name << " point " << i;
        }
    }
}

TEST(PclCompat, WeReadWhatPclWritesExactlyAsPclReadsIt) {
    test::TempDir dir;
    const auto cloud = typed_cloud();
    pcl::PCDWriter w;
    const std::string files[] = {dir.file("a.pcd"), dir.file("b.pcd"), dir.file("c.pcd")};
    ASSERT_EQ(w.writeASCII(files[0], cloud), 0);
    ASSERT_EQ(w.writeBinary(files[1], cloud), 0);
    ASSERT_EQ(w.writeBinaryCompressed(files[2], cloud), 0);
    for (const auto& f : files) {
        pcl::PCLPointCloud2 theirs;
        ASSERT_EQ(pcl::io::loadPCDFile(f, theirs), 0) << f;
        const ReadResult ours = read_cloud(f);
        expect_same_fields(ours.blob.cloud, theirs);
    }
}

TEST(PclCompat, PclReadsWhatWeWriteAsWeDo) {
    test::TempDir dir;
    pcl::PCLPointCloud2 blob2;
    pcl::toPCLPointCloud2(typed_cloud(), blob2);
    Blob blob;
    blob.cloud = blob2;
    for (const auto& [enc, name] : {std::pair{PcdEncoding::kAscii, "a"},
                                    {PcdEncoding::kBinary, "b"},
                                    {PcdEncoding::kBinaryCompressed, "c"}}) {
        StringSink sink;
        write_pcd(blob, enc, sink);
        const std::string path = dir.file(std::string(name) + ".pcd");
        test::spit(path, sink.out);
        pcl::PCLPointCloud2 theirs;
        ASSERT_EQ(pcl::io::loadPCDFile(path, theirs), 0) << name;
        expect_same_fields(blob.cloud, theirs);
        pcl::PointCloud<pcl::PointXYZRGBNormal> typed;
        pcl::fromPCLPointCloud2(theirs, typed);
        EXPECT_EQ(typed[3].rgba, typed_cloud()[3].rgba) << name;
    }
}

}  // namespace
}  // namespace pc::io
