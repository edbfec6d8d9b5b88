#include "saved_run.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "cyclone/detail/byte_fields.h"
#include "scene.h"

namespace cyclone::scene {
namespace {

// Tag, the scene text's hash, the steps taken, a checksum of those three; then the
// World's state, which carries its own checksum.
constexpr char kTag[8] = {'C', 'Y', 'R', 'U', 'N', 'v', '0', '1'};
constexpr std::size_t kHeaderSize = 8 + 8 + 8 + 8;

std::uint64_t hashBytes(const std::uint8_t *data, std::size_t size, std::uint64_t h = 0xCBF29CE484222325ull) {
    for (std::size_t k = 0; k < size; ++k) h = (h ^ data[k]) * 0x100000001B3ull;
    return h;
}

std::uint64_t sceneHash(const std::string &text) {
    return hashBytes(reinterpret_cast<const std::uint8_t *>(text.data()), text.size());
}

}  // namespace

std::vector<std::uint8_t> savedRunBytes(const std::string &sceneText, std::int64_t stepsDone, const World &world) {
    const std::vector<std::uint8_t> state = world.saveState();
    std::vector<std::uint8_t> out(kHeaderSize + state.size());
    std::memcpy(out.data(), kTag, sizeof kTag);
    detail::put(out, 8, sceneHash(sceneText));
    detail::put(out, 16, stepsDone);
    detail::put(out, 24, hashBytes(out.data(), 24));
    if (!state.empty()) std::memcpy(out.data() + kHeaderSize, state.data(), state.size());
    return out;
}

std::int64_t resumeSavedRun(const std::vector<std::uint8_t> &bytes, const std::string &sceneText, World &world) {
    if (bytes.size() < kHeaderSize || std::memcmp(bytes.data(), kTag, sizeof kTag) != 0)
        throw SavedRunError("is not a state saved by cyclone-world --save-state");
    if (detail::take<std::uint64_t>(bytes, 24) != hashBytes(bytes.data(), 24))
        throw SavedRunError("is damaged: its header's checksum fails");
    if (detail::take<std::uint64_t>(bytes, 8) != sceneHash(sceneText))
        throw SavedRunError("was saved from another scene (the scene file's text differs)");
    const auto steps = detail::take<std::int64_t>(bytes, 16);
    if (steps < 0 || steps > kMaxSteps) throw SavedRunError("is damaged: it says " + std::to_string(steps) + " steps");
    try {
        world.restoreState(std::vector<std::uint8_t>(bytes.begin() + kHeaderSize, bytes.end()));
    } catch (const InvalidArgument &error) {
        throw SavedRunError(error.problem());
    }
    return steps;
}

std::vector<std::uint8_t> readSavedRun(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SavedRunError(std::string("cannot read: ") + std::strerror(errno));
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw SavedRunError("cannot read: read error");
    return bytes;
}

}  // namespace cyclone::scene
