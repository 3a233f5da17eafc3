// libFuzzer target: the JSON readers (nerfstudio's dataparser_transforms.json, pc_synth's
// ground truth, the cameras' transforms.json and dataparser_transforms.json). Any input must parse
// or throw pc::Error; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <pc/cameras/read_cameras.h>
#include <pc/core/error.h>
#include <pc/evaluation/truth.h>
#include <pc/features/transform.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        (void)pc::features::nerfstudio_forward(text, "fuzz");
    } catch (const pc::Error&) {
    }
    try {
        (void)pc::evaluation::parse_truth(text);
    } catch (const pc::Error&) {
    }
    try {
        (void)pc::cameras::parse_transforms(text, "fuzz");
    } catch (const pc::Error&) {
    }
    try {
        (void)pc::cameras::parse_dataparser_transforms(text, "fuzz");
    } catch (const pc::Error&) {
    }
    return 0;
}
