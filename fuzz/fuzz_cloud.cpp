// libFuzzer target: the cloud readers (PCD ascii/binary/compressed, PLY, XYZ text), each by its
// own entry and through parse_cloud()'s recognition by content. Any input must parse or throw
// pc::Error; anything else (a crash, a sanitizer report, another exception) is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <pc/core/error.h>
#include <pc/io/pcd.h>
#include <pc/io/ply.h>
#include <pc/io/read.h>
#include <pc/io/text.h>

namespace {

template <class Parse>
void try_parse(Parse parse, std::string_view bytes) {
    try {
        const pc::io::ReadResult r = parse(bytes);
        pc::io::check_layout(r.blob);  // what a reader returns must be consistent
    } catch (const pc::Error&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try_parse(pc::io::parse_cloud, bytes);
    try_parse(pc::io::parse_pcd, bytes);
    try_parse(pc::io::parse_ply, bytes);
    try_parse(pc::io::parse_text, bytes);
    return 0;
}
