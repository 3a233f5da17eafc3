// Image files for the view tools (pc_lift, pc_maskeval): read with OpenCV, one clear error line.
#pragma once

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <pc/core/error.h>

namespace pc::tools {

/// An 8- or 16-bit image as stored (channels in OpenCV's BGR order); pc::IoError naming the file
/// when it is missing, unreadable or of another sample type.
inline cv::Mat read_image(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw IoError(path + ": no such image file");
    }
    const cv::Mat m = cv::imread(path, cv::IMREAD_UNCHANGED);
    if (m.empty()) {
        throw IoError(path + ": not an image OpenCV can read");
    }
    if (m.depth() != CV_8U && m.depth() != CV_16U) {
        throw IoError(path + ": only 8- and 16-bit images are supported");
    }
    return m;
}

/// The file's extension in lower case (".png", ".jpg", ...).
inline std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

inline bool is_jpeg(const std::string& path) {
    const std::string ext = lower_extension(path);
    return ext == ".jpg" || ext == ".jpeg";
}

/// FruitNeRF's rule for binary masks: a JPEG is fruit where its value is > 125 (compression blurs
/// 0/255), any other image where it is not 0 (0/1, 0/255, or 8- or 16-bit instance ids); several
/// channels: their largest value. 255 where fruit, else 0; row-major.
inline std::vector<std::uint8_t> binary_mask(const cv::Mat& m, const std::string& path) {
    cv::Mat grey = m;
    if (m.channels() > 1) {
        std::vector<cv::Mat> planes;
        cv::split(m, planes);
        grey = planes[0];
        for (std::size_t c = 1; c < planes.size(); ++c) {
            cv::max(grey, planes[c], grey);
        }
    }
    cv::Mat fruit;
    cv::compare(grey, is_jpeg(path) ? 125 : 0, fruit, cv::CMP_GT);
    std::vector<std::uint8_t> out(static_cast<std::size_t>(m.cols) *
                                  static_cast<std::size_t>(m.rows));
    for (int y = 0; y < m.rows; ++y) {
        std::memcpy(out.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(m.cols),
                    fruit.ptr<std::uint8_t>(y), static_cast<std::size_t>(m.cols));
    }
    return out;
}

/// The ids of a one-channel 8- or 16-bit instance mask (0: no fruit), row-major; pc::IoError
/// naming the file for several channels or a JPEG (compression changes ids).
inline std::vector<std::uint32_t> instance_ids(const cv::Mat& m, const std::string& path) {
    if (m.channels() != 1) {
        throw IoError(path + ": instance masks must have one channel");
    }
    if (is_jpeg(path)) {
        throw IoError(path + ": instance masks must be PNG (JPEG compression changes the ids)");
    }
    std::vector<std::uint32_t> out;
    out.reserve(static_cast<std::size_t>(m.rows) * static_cast<std::size_t>(m.cols));
    for (int y = 0; y < m.rows; ++y) {
        for (int x = 0; x < m.cols; ++x) {
            out.push_back(m.depth() == CV_8U ? m.ptr<std::uint8_t>(y)[x]
                                             : m.ptr<std::uint16_t>(y)[x]);
        }
    }
    return out;
}

}  // namespace pc::tools
