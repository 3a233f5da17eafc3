#pragma once
// The project's own corpus of malformed and edge-case inputs (docs/formats.md lists the cases).
// Generated here, never downloaded; each entry is a name and the exact bytes.

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace pc::test {

struct CorpusFile {
    std::string name;
    std::string bytes;
};

inline std::string pcd_header(const std::string& fields,
                              const std::string& size,
                              const std::string& type,
                              const std::string& count,
                              const std::string& width,
                              const std::string& points,
                              const std::string& data,
                              const std::string& height = "1") {
    return "# .PCD v0.7\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " + type +
           "\nCOUNT " + count + "\nWIDTH " + width + "\nHEIGHT " + height +
           "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + points + "\nDATA " + data + "\n";
}

inline std::string xyz_header(const std::string& n, const std::string& data) {
    return pcd_header("x y z", "4 4 4", "F F F", "1 1 1", n, n, data);
}

inline std::string floats(std::initializer_list<float> v) {
    std::string s(v.size() * 4, '\0');
    std::memcpy(s.data(), v.begin(), s.size());
    return s;
}

inline std::string u32(std::uint32_t v) { return std::string(reinterpret_cast<char*>(&v), 4); }

inline std::string ply_header(const std::string& format,
                              const std::string& count,
                              const std::string& props) {
    return "ply\nformat " + format + " 1.0\nelement vertex " + count + "\n" + props +
           "end_header\n";
}

/// Inputs every reader must reject with a clear message (exit 1 in a tool).
inline std::vector<CorpusFile> malformed_corpus() {
    const std::string xyz_props = "property float x\nproperty float y\nproperty float z\n";
    std::mt19937 rng(7);
    std::string noise(200, '\0');
    for (char& c : noise) {
        c = static_cast<char>(rng() & 0xff);
    }
    noise[0] = '\x93';  // not "ply", not a PCD keyword, not a number
    return {
        {"empty", ""},
        {"text_garbage", "hello world, this is not a cloud\n"},
        {"random_bytes", noise},
        {"no_data_line", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\n"},
        {"no_fields", "VERSION 0.7\nSIZE 4\nTYPE F\nWIDTH 1\nPOINTS 1\nDATA ascii\n1\n"},
        {"size_arity", pcd_header("x y z", "4 4", "F F F", "1 1 1", "1", "1", "ascii") + "1 2 3\n"},
        {"type_arity", pcd_header("x y z", "4 4 4", "F F", "1 1 1", "1", "1", "ascii") + "1 2 3\n"},
        {"count_arity",
         pcd_header("x y z", "4 4 4", "F F F", "1 1", "1", "1", "ascii") + "1 2 3\n"},
        {"unknown_type",
         pcd_header("x y z", "4 4 4", "F X F", "1 1 1", "1", "1", "ascii") + "1 2 3\n"},
        {"bad_type_size",
         pcd_header("x y z", "4 2 4", "F F F", "1 1 1", "1", "1", "ascii") + "1 2 3\n"},
        {"count_zero", pcd_header("x y z", "4 4 4", "F F F", "1 0 1", "1", "1", "ascii") + "1 3\n"},
        {"count_negative",
         pcd_header("x y z", "4 4 4", "F F F", "1 -1 1", "1", "1", "ascii") + "1 2 3\n"},
        {"points_negative",
         pcd_header("x y z", "4 4 4", "F F F", "1 1 1", "1", "-1", "ascii") + "1 2 3\n"},
        {"points_lie",
         pcd_header("x y z", "4 4 4", "F F F", "1 1 1", "2", "3", "ascii") + "1 2 3\n4 5 6\n"},
        {"wh_wraps_32bit",
         pcd_header("x y z", "4 4 4", "F F F", "1 1 1", "65536", "0", "binary", "65536")},
        {"billions_claimed", xyz_header("4000000000", "binary") + floats({1, 2, 3, 4, 5, 6})},
        {"width_too_big", xyz_header("1099511627776", "binary") + floats({1, 2, 3})},
        {"binary_truncated", xyz_header("3", "binary") + floats({1, 2, 3, 4, 5, 6, 7})},
        {"ascii_truncated", xyz_header("3", "ascii") + "1 2 3\n4 5 6\n"},
        {"ascii_short_row", xyz_header("2", "ascii") + "1 2 3\n4 5\n"},
        {"ascii_long_row", xyz_header("2", "ascii") + "1 2 3\n4 5 6 7\n"},
        {"ascii_not_numeric", xyz_header("2", "ascii") + "1 2 3\n4 abc 6\n"},
        {"ascii_decimal_comma", xyz_header("1", "ascii") + "1,5 2 3\n"},
        {"ascii_extra_row", xyz_header("1", "ascii") + "1 2 3\n4 5 6\n"},
        {"ascii_unsigned_negative",
         pcd_header("x label", "4 4", "F U", "1 1", "1", "1", "ascii") + "1 -1\n"},
        {"ascii_u8_overflow",
         pcd_header("x v", "4 1", "F U", "1 1", "1", "1", "ascii") + "1 300\n"},
        {"unknown_data_kind", xyz_header("1", "binaryx") + floats({1, 2, 3})},
        {"duplicate_field",
         pcd_header("x y x", "4 4 4", "F F F", "1 1 1", "1", "1", "ascii") + "1 2 3\n"},
        {"unknown_keyword",
         "VERSION 0.7\nFIELDS x\nSIZE 4\nTYPE F\nFOO 1\nWIDTH 1\nPOINTS 1\nDATA ascii\n1\n"},
        {"viewpoint_short",
         "VERSION 0.7\nFIELDS x\nSIZE 4\nTYPE F\nWIDTH 1\nVIEWPOINT 0 0 0\nPOINTS 1\nDATA "
         "ascii\n1\n"},
        {"compressed_prefix_short", xyz_header("1", "binary_compressed") + "\x05\x00"},
        {"compressed_usize_lies",
         xyz_header("2", "binary_compressed") + u32(25) + u32(100) + std::string(25, '\x1f')},
        {"compressed_csize_lies",
         xyz_header("1", "binary_compressed") + u32(1000) + u32(12) + std::string(13, '\x0b')},
        {"compressed_backref_before_start",
         xyz_header("1", "binary_compressed") + u32(2) + u32(12) + std::string("\xe0\x10", 2)},
        {"compressed_zero_csize", xyz_header("1", "binary_compressed") + u32(0) + u32(12)},
        {"ply_vertex_count_too_big",
         ply_header("binary_little_endian", "3", xyz_props) + floats({1, 2, 3, 4, 5, 6})},
        {"ply_vertices_after_an_element_truncated",
         "ply\nformat binary_little_endian 1.0\nelement extra 2\nproperty float a\nelement vertex "
         "2\n" +
             xyz_props + "end_header\n" + floats({9, 9, 1, 2, 3, 4})},
        {"ply_vertex_count_too_small",
         ply_header("binary_little_endian", "1", xyz_props) + floats({1, 2, 3, 4, 5, 6})},
        {"ply_unknown_type", ply_header("binary_little_endian", "1",
                                        "property float x\nproperty quad y\nproperty float z\n") +
                                 floats({1, 2, 3})},
        {"ply_vertex_list",
         ply_header("ascii", "1", xyz_props + "property list uchar int idx\n") + "1 2 3 1 5\n"},
        {"ply_no_end_header", "ply\nformat ascii 1.0\nelement vertex 1\n" + xyz_props + "1 2 3\n"},
        {"ply_negative_count",
         ply_header("binary_little_endian", "-1", xyz_props) + floats({1, 2, 3})},
        {"ply_huge_count",
         ply_header("binary_little_endian", "1099511627776", xyz_props) + floats({1, 2, 3})},
        {"ply_ascii_short_row", ply_header("ascii", "2", xyz_props) + "1 2 3\n4 5\n"},
        {"ply_no_x", ply_header("ascii", "1", "property float y\nproperty float z\n") + "2 3\n"},
        {"ply_bad_format", "ply\nformat binary_middle_endian 1.0\nelement vertex 1\n" + xyz_props +
                               "end_header\n" + floats({1, 2, 3})},
        {"text_ragged", "1 2 3\n4 5 6\n7 8\n"},
        {"text_five_columns", "1 2 3 4 5\n"},
        {"text_not_numeric", "1 2 3\n4 five 6\n"},
        {"text_colour_out_of_range", "1 2 3 255 0 300\n"},
    };
}

/// Valid inputs with the oddities real files carry; each must load (exit 0) with `points` points.
struct EdgeFile {
    std::string name;
    std::string bytes;
    std::size_t points;
};

inline std::vector<EdgeFile> edge_corpus() {
    // 13.265934f is stored as the bytes 'D' 'A' 'T' 'A' (0x41544144): PCL 1.13 chokes on it.
    const float data_float = 13.265934f;
    return {
        {"crlf",
         "VERSION 0.7\r\nFIELDS x y z\r\nSIZE 4 4 4\r\nTYPE F F F\r\nCOUNT 1 1 1\r\nWIDTH 2\r\n"
         "HEIGHT 1\r\nPOINTS 2\r\nDATA ascii\r\n1 2 3\r\n4 5 6\r\n",
         2},
        {"comments_blank_lines",
         "# hello\n\nVERSION 0.7\n# more\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
         "WIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n1  2\t3\n\n4 5 6\n\n",
         2},
        {"version_05_no_count",
         "# .PCD v.5 - Point Cloud Data file format\nFIELDS x y z\nSIZE 4 4 4\n"
         "TYPE F F F\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n1 2 3\n4 5 6\n",
         2},
        {"nan_inf_ascii", xyz_header("2", "ascii") + "nan 2 inf\n-inf NaN 3\n", 2},
        {"trailing_bytes", xyz_header("1", "binary") + floats({1, 2, 3}) + std::string(4096, '\0'),
         1},
        {"binary_spelling_DATA", xyz_header("2", "binary") + floats({data_float, 1, 2, 3, 4, 5}),
         2},
        {"zero_points_binary", xyz_header("0", "binary"), 0},
        {"zero_points_compressed", xyz_header("0", "binary_compressed") + u32(0) + u32(0), 0},
        {"organised_with_nan",
         pcd_header("x y z", "4 4 4", "F F F", "1 1 1", "2", "4", "ascii", "2") +
             "1 1 1\nnan nan nan\n2 2 2\n3 3 3\n",
         4},
        {"padding_field",
         pcd_header("x y z _", "4 4 4 1", "F F F U", "1 1 1 4", "1", "1", "ascii") +
             "1 2 3 0 0 0 0\n",
         1},
        {"text_xyz", "# x y z\n1 2 3\n4,5,6\n", 2},
        {"text_with_names", "x y z r g b\n1 2 3 255 0 0\n", 1},
    };
}

}  // namespace pc::test
