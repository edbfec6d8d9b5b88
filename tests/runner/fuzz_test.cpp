// Fuzzing the runner with mutated versions of the shipped scenes: deleted fields, wrong
// types, extreme and non-finite numbers, duplicated and emptied parts, truncated text and
// flipped bytes. Whatever the input, the only outcomes are 0 (ran), 2 (refused, with one
// line) and 3 (became non-finite). Deterministic: a fixed seed and our own draws.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <iterator>
#include <map>
#include <sstream>

#include "cli.h"
#include "runner_test_support.h"
#include "../sanitized_build.h"

namespace {

using namespace runner_test;
using namespace cyclone::scene;
using nlohmann::json;

// Sanitized builds run about ten times slower; they fuzz fewer inputs in the same time.
constexpr int kScale = cyclone::test::kSanitized ? 4 : 1;

// The first eight hold the format's first version; the others its second: ball, hinge,
// slider and distance joints (chain-20, crane, door, ragdoll-stairs; the joint mutation
// below makes fixed ones too), kinematic motion (elevator), a sensor on a layer
// (trigger-zone), a compound (table-and-chair) and a mesh under round shapes
// (rolling-on-mesh).
const char *const kScenes[] = {"tower",          "pyramid-20", "pyramid-10",   "resting-shapes", "incline",
                               "sleep-wake",     "springs",    "mixed-shapes", "chain-20",       "crane",
                               "door",           "elevator",   "trigger-zone", "table-and-chair", "rolling-on-mesh",
                               "ragdoll-stairs"};

// splitmix64: the same numbers on every platform and standard library.
class Draw {
public:
    explicit Draw(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }
    bool chance(int percent) { return below(100) < static_cast<std::size_t>(percent); }

private:
    std::uint64_t state_;
};

// Number literals that probe the edges: written into the text so that 1e999 stays 1e999.
const char *const kExtremeNumbers[] = {"0",     "-0",      "-1",     "1e999",   "-1e999",  "1e308",
                                       "-1e308", "1e-308", "5e-324", "1e300",   "-1e300",  "9223372036854775807",
                                       "18446744073709551616", "-9223372036854775809", "4294967296", "2147483648",
                                       "0.5",   "1.5",     "1e15",   "123456789012345678901234567890", "NaN", "Infinity"};

const char *const kWrongValues[] = {"null", "true", "false", "\"\"", "\"box\"", "\"ground\"", "[]", "{}",
                                    "[1, 2]", "[[0, 0, 0]]", "{\"type\": \"sphere\"}", "[0, 0, 0, 0]"};

struct Node {
    json *value;
    json *parent;
    std::string key;     // when the parent is an object
    std::size_t index;   // when the parent is an array
};

void collect(json &value, json *parent, const std::string &key, std::size_t index, std::vector<Node> &nodes) {
    nodes.push_back({&value, parent, key, index});
    if (value.is_object()) {
        for (auto it = value.begin(); it != value.end(); ++it) collect(it.value(), &value, it.key(), 0, nodes);
    } else if (value.is_array()) {
        for (std::size_t i = 0; i < value.size(); ++i) collect(value[i], &value, "", i, nodes);
    }
}

// A placeholder that survives dump() and is then replaced by a raw literal.
constexpr const char *kRawMarker = "@@RAW@@";

std::string replaceRaw(std::string text, const std::string &literal) {
    const std::string quotedMarker = std::string("\"") + kRawMarker + "\"";
    const auto at = text.find(quotedMarker);
    if (at != std::string::npos) text.replace(at, quotedMarker.size(), literal);
    return text;
}

// A key as a typist gets it wrong: a letter dropped, doubled, swapped with the next, or
// capitalised.
std::string misspell(std::string key, Draw &draw) {
    if (key.empty()) return "x";
    const std::size_t at = draw.below(key.size());
    switch (draw.below(4)) {
    case 0: key.erase(at, 1); break;
    case 1: key.insert(at, 1, key[at]); break;
    case 2:
        if (at + 1 < key.size()) std::swap(key[at], key[at + 1]);
        break;
    case 3: key[at] = static_cast<char>(std::toupper(static_cast<unsigned char>(key[at]))); break;
    }
    return key;
}

// Body fields of the format's second version, with good and bad values.
const char *const kSecondVersionFields[] = {"motion", "layer", "collides_with", "sensor", "rolling_friction",
                                            "spinning_friction"};
const char *const kSecondVersionValues[] = {"\"kinematic\"", "\"dynamic\"", "3", "-1", "40", "[0, 1]", "true",
                                            "0.01", "-0.5", "\"static\""};

// Joint fields, with good and bad values: another type, a body that is not there or the
// world, a zero axis, reversed limits, a motor without force, a negative stiffness.
const char *const kJointFields[] = {"type", "a", "b", "anchor", "anchor_b", "axis", "limits", "motor",
                                    "min_distance", "max_distance", "stiffness", "damping", "break_force",
                                    "collide_connected"};
const char *const kJointValues[] = {"\"ball\"", "\"hinge\"", "\"fixed\"", "\"slider\"", "\"distance\"",
                                    "\"weld\"", "null", "\"nobody\"", "[0, 0, 0]", "[0, 1, 0]", "[1, -1]",
                                    "[-0.5, 0.5]", "{\"speed\": 1, \"max_force\": 0}",
                                    "{\"speed\": -1e300, \"max_force\": 1e300}", "-1", "0", "2", "1e-300",
                                    "true"};

// Sets one of `fields` of an element of the document's list `list` (when it has one) to
// one of `values`.
template <std::size_t F, std::size_t V>
void setSomeField(json &doc, const char *list, const char *const (&fields)[F], const char *const (&values)[V],
                  Draw &draw) {
    if (!doc.is_object() || !doc.contains(list) || !doc[list].is_array() || doc[list].empty()) return;
    json &element = doc[list][draw.below(doc[list].size())];
    if (element.is_object()) element[fields[draw.below(F)]] = json::parse(values[draw.below(V)]);
}

// One structural mutation of the document, returned as text.
std::string mutateStructure(const json &original, Draw &draw) {
    json doc = original;
    std::vector<Node> nodes;
    collect(doc, nullptr, "", 0, nodes);
    const int rounds = 1 + static_cast<int>(draw.below(3));
    std::string literal;
    for (int round = 0; round < rounds; ++round) {
        nodes.clear();
        collect(doc, nullptr, "", 0, nodes);
        const Node node = nodes[draw.below(nodes.size())];
        switch (draw.below(11)) {
        case 0:  // delete
            if (node.parent && node.parent->is_object()) {
                node.parent->erase(node.key);
            } else if (node.parent) {
                node.parent->erase(node.index);
            }
            break;
        case 1:  // wrong type
            *node.value = json::parse(kWrongValues[draw.below(std::size(kWrongValues))]);
            break;
        case 2:  // extreme or non-finite number, written raw
            if (literal.empty()) {
                literal = kExtremeNumbers[draw.below(std::size(kExtremeNumbers))];
                *node.value = kRawMarker;
            }
            break;
        case 3:  // scale a number
            if (node.value->is_number()) *node.value = node.value->get<double>() * (draw.chance(50) ? -1e6 : 1e-6);
            break;
        case 4:  // duplicate an element (duplicate names, shared events)
            if (node.parent && node.parent->is_array()) node.parent->push_back(*node.value);
            break;
        case 5:  // empty a container
            if (node.value->is_array()) *node.value = json::array();
            if (node.value->is_object()) *node.value = json::object();
            break;
        case 6:  // a name where there was a name, or a value moved elsewhere
            if (node.value->is_string()) {
                *node.value = nodes[draw.below(nodes.size())].value->is_string()
                                  ? *nodes[draw.below(nodes.size())].value
                                  : json("box3");
            } else {
                *node.value = *nodes[draw.below(nodes.size())].value;
            }
            break;
        case 7:  // a body thrown absurdly fast: a blow-up
            if (doc.is_object() && doc.contains("bodies") && doc["bodies"].is_array() && !doc["bodies"].empty()) {
                json &body = doc["bodies"][draw.below(doc["bodies"].size())];
                const double speeds[] = {1e300, -1e300, 1e200, 1e150, 1e30};
                if (body.is_object()) body["velocity"] = {speeds[draw.below(std::size(speeds))], 0, 0};
            }
            break;
        case 8:  // a misspelt key: a warning, or with --strict a refusal
            if (node.parent && node.parent->is_object()) {
                json moved = *node.value;
                const std::string key = node.key;
                node.parent->erase(key);
                (*node.parent)[misspell(key, draw)] = std::move(moved);
            }
            break;
        case 9:  // a field of the second version on a body
            setSomeField(doc, "bodies", kSecondVersionFields, kSecondVersionValues, draw);
            break;
        case 10:  // a joint's field given another value, good or bad
            setSomeField(doc, "joints", kJointFields, kJointValues, draw);
            break;
        }
    }
    std::string text = doc.dump();
    return literal.empty() ? text : replaceRaw(text, literal);
}

// One textual mutation: truncation, flipped or inserted bytes, a deleted range.
std::string mutateText(std::string text, Draw &draw) {
    if (text.empty()) return text;
    switch (draw.below(4)) {
    case 0: text.resize(draw.below(text.size())); break;
    case 1:
        for (std::size_t flips = 1 + draw.below(4); flips > 0; --flips) {
            text[draw.below(text.size())] = static_cast<char>(draw.below(256));
        }
        break;
    case 2: {
        const std::string noise[] = {"{", "}", "[", "]", ",", ":", "\"", "\\", "1e999", "\xff", std::string(1, '\0'), "-", "null"};
        text.insert(draw.below(text.size()), noise[draw.below(std::size(noise))]);
        break;
    }
    case 3: {
        const std::size_t at = draw.below(text.size());
        text.erase(at, draw.below(64));
        break;
    }
    }
    return text;
}

std::string mutate(const std::string &text, const json &document, Draw &draw) {
    return draw.chance(70) ? mutateStructure(document, draw) : mutateText(text, draw);
}

std::vector<std::string> linesOf(const std::string &text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// Whether an exit-2 stderr is a located refusal: its last line "FILE: PLACE: message" with a
// place of the scene file (a JSON path, "(top level)") or of the run ("step N"), never the
// bare "run" of old, and any line before it a warning about an unknown field.
::testing::AssertionResult locatedRefusal(const std::string &err, const std::string &file) {
    const std::vector<std::string> lines = linesOf(err);
    if (lines.empty()) return ::testing::AssertionFailure() << "no message";
    const std::string prefix = file + ": ";
    for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
        const bool warning = lines[i].find(": unknown field") != std::string::npos ||
                             lines[i].find(": not a field of ") != std::string::npos ||
                             lines[i].find(" more unknown fields") != std::string::npos;
        if (!warning) return ::testing::AssertionFailure() << "a line before the refusal: " << lines[i];
    }
    const std::string &last = lines.back();
    if (last.rfind(prefix, 0) != 0) return ::testing::AssertionFailure() << "not FILE: ...: " << last;
    const std::string rest = last.substr(prefix.size());
    if (rest.rfind("(top level): ", 0) == 0) return ::testing::AssertionSuccess();
    if (rest.rfind("step ", 0) == 0) {
        if (rest.find(": the world could not take this step") != std::string::npos) return ::testing::AssertionSuccess();
        return ::testing::AssertionFailure() << "a step without its failure: " << last;
    }
    // A JSON path: a member of the document (a name, or a quoted key in brackets) first.
    const char first = rest.empty() ? ' ' : rest[0];
    if ((std::isalpha(static_cast<unsigned char>(first)) || first == '_' || first == '[') && rest.find(": ") != std::string::npos &&
        rest.rfind("run: ", 0) != 0) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "no place of the scene: " << last;
}

std::string countsText(const std::map<int, int> &counts) {
    std::ostringstream out;
    for (const auto &[status, count] : counts) out << " exit " << status << ": " << count;
    return out.str();
}

TEST(Fuzz, ThousandsOfMutatedScenesInProcess) {
    constexpr int kPerScene = 1000 / kScale;
    Draw draw(0x5eed2024);
    std::map<int, int> counts;
    int strictRefusals = 0;
    int jointRefusals = 0;  // refused at a place in "joints"
    TempDir dir;
    Invocation invocation;
    invocation.command = Invocation::Command::Run;
    invocation.scene = "fuzz.json";
    invocation.steps = 3;
    invocation.quiet = true;
    const auto start = std::chrono::steady_clock::now();
    for (const char *name : kScenes) {
        const std::string text = readText(scenePath(name));
        const json document = json::parse(text);
        for (int i = 0; i < kPerScene; ++i) {
            const std::string mutated = mutate(text, document, draw);
            // One run in four writes outputs, one in five is --strict.
            const bool outputs = draw.chance(25);
            invocation.summary = outputs ? dir.file("s.json") : "";
            invocation.trace = outputs ? dir.file("t.csv") : "";
            invocation.strict = draw.chance(20);
            // A crash leaves no message: CYCLONE_FUZZ_LAST=FILE keeps the input being run.
            if (const char *last = std::getenv("CYCLONE_FUZZ_LAST")) writeText(last, mutated);
            std::ostringstream out, err;
            const int status = runSceneText(mutated, invocation, out, err, false);
            ++counts[status];
            ASSERT_TRUE(status == 0 || status == 2 || status == 3) << status << " for:\n" << mutated;
            if (status == 2) {
                ASSERT_TRUE(locatedRefusal(err.str(), "fuzz.json")) << "for:\n" << mutated;
                if (err.str().find("(refused by --strict") != std::string::npos) ++strictRefusals;
                if (err.str().find("fuzz.json: joints[") != std::string::npos) ++jointRefusals;
                ASSERT_TRUE(dir.files().empty()) << err.str() << "for:\n" << mutated;
            } else {
                ASSERT_EQ(dir.files().size(), outputs ? 2u : 0u) << err.str();
            }
            for (const std::string &file : dir.files()) fs::remove(dir.file(file));
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[ fuzz     ] " << kPerScene * std::size(kScenes) << " in-process mutations in " << seconds
              << " s:" << countsText(counts) << " (" << strictRefusals << " refused by --strict, " << jointRefusals
              << " at a joint)\n";
    EXPECT_GT(counts[0], 0);
    EXPECT_GT(counts[2], 0);
    EXPECT_GT(counts[3], 0);
    EXPECT_GT(strictRefusals, 0);
    EXPECT_GT(jointRefusals, 0);
}

TEST(Fuzz, HundredsOfMutatedScenesThroughTheExecutable) {
    constexpr int kPerScene = 40 / kScale;
    Draw draw(0xc0ffee);
    std::map<int, int> counts;
    TempDir dir;
    const std::string scene = dir.file("fuzz.json");
    const std::string summary = dir.file("s.json");
    const std::string trace = dir.file("t.csv");
    for (const char *name : kScenes) {
        const std::string text = readText(scenePath(name));
        const json document = json::parse(text);
        for (int i = 0; i < kPerScene; ++i) {
            const std::string mutated = mutate(text, document, draw);
            writeText(scene, mutated);
            const Process p = runWorld({"run", scene, "--steps", "3", "--summary", summary, "--trace", trace}, dir);
            ++counts[p.status];
            ASSERT_TRUE(p.status == 0 || p.status == 2 || p.status == 3) << p.status << " " << p.err << " for:\n" << mutated;
            const bool wrote = fs::exists(summary) && fs::exists(trace);
            if (p.status == 2) {
                ASSERT_TRUE(locatedRefusal(p.err, scene)) << "for:\n" << mutated;
                ASSERT_FALSE(fs::exists(summary) || fs::exists(trace)) << p.err;
            } else {
                ASSERT_TRUE(wrote);
                const json written = json::parse(readText(summary));
                ASSERT_EQ(written["metrics"]["non_finite"].get<bool>(), p.status == 3);
            }
            ASSERT_EQ(dir.files().size(), wrote ? 3u : 1u);
            fs::remove(summary);
            fs::remove(trace);
        }
    }
    std::cout << "[ fuzz     ] " << kPerScene * std::size(kScenes) << " mutations through cyclone-world:"
              << countsText(counts) << "\n";
    EXPECT_GT(counts[0], 0);
    EXPECT_GT(counts[2], 0);
}

// Scenes of the kinds the third hostile campaign built (issue 61), with drawn sizes and
// counts: ropes of light beads holding a heavy ball (ball or distance joints, mass ratios
// up to 1:10,000), bodies spawned at one point on a box, mesh or plane floor, thin rods and
// needles, compounds with children far out, and steps near and below the shortest. Each
// runs or is refused with one located line; nothing crashes.
json floorOf(int kind) {
    if (kind == 0) return {{"name", "floor"}, {"static", true}, {"shape", {{"type", "box"}, {"half_extents", {20, 0.1, 20}}}},
                           {"position", {0, -0.1, 0}}};
    if (kind == 1)
        return {{"name", "floor"}, {"static", true},
                {"shape", {{"type", "mesh"}, {"vertices", {{-20, 0, -20}, {20, 0, -20}, {20, 0, 20}, {-20, 0, 20}}},
                           {"triangles", {{0, 2, 1}, {0, 3, 2}}}}}};
    return {{"name", "floor"}, {"static", true}, {"shape", {{"type", "plane"}, {"normal", {0, 1, 0}}, {"offset", 0}}}};
}

json roundShape(Draw &draw, double size) {
    switch (draw.below(4)) {
    case 0: return {{"type", "sphere"}, {"radius", size}};
    case 1: return {{"type", "capsule"}, {"radius", size}, {"length", 3 * size}};
    case 2: return {{"type", "cylinder"}, {"radius", size}, {"length", 3 * size}};
    default:
        return {{"type", "compound"},
                {"children", {{{"shape", {{"type", "box"}, {"half_extents", {size, size / 2, size / 2}}}}, {"position", {0, 0, 0}}},
                              {{"shape", {{"type", "sphere"}, {"radius", size / 2}}}, {"position", {size, 0, 0}}}}}};
    }
}

json rope(Draw &draw) {
    const double ratios[] = {1, 100, 1000, 10000};
    const int beads = 2 + static_cast<int>(draw.below(19));
    const double gap = 0.25;
    json bodies = json::array(), joints = json::array();
    const bool distance = draw.chance(50);
    for (int i = 0; i <= beads; ++i) {
        const bool ball = i == beads;
        bodies.push_back({{"name", "b" + std::to_string(i)}, {"mass", ball ? 0.1 * ratios[draw.below(4)] : 0.1},
                          {"shape", {{"type", "sphere"}, {"radius", ball ? 0.2 : 0.05}}},
                          {"position", {gap * (i + 1), 5, 0}}});
        json joint = {{"name", "j" + std::to_string(i)}, {"type", distance ? "distance" : "ball"},
                      {"a", "b" + std::to_string(i)}, {"b", i == 0 ? json(nullptr) : json("b" + std::to_string(i - 1))},
                      {"anchor", {gap * (i + 1), 5, 0}}};
        if (distance) joint["anchor_b"] = {gap * i, 5, 0};
        joints.push_back(joint);
    }
    return {{"bodies", bodies}, {"joints", joints}};
}

json onePointSpawn(Draw &draw) {
    const int count = 2 + static_cast<int>(draw.below(30));
    const double size = 0.1 + 0.1 * static_cast<double>(draw.below(3));
    json shape = roundShape(draw, size);
    json bodies = json::array({floorOf(static_cast<int>(draw.below(3)))});
    for (int i = 0; i < count; ++i)
        bodies.push_back({{"name", "s" + std::to_string(i)}, {"shape", shape}, {"position", {0, size, 0}}});
    return {{"bodies", bodies}};
}

json thinShape(Draw &draw) {
    const double radii[] = {1e-4, 5e-4, 1e-3, 2e-3, 1e-2};
    const double r = radii[draw.below(5)];
    json shape = draw.chance(50) ? json{{"type", "cylinder"}, {"radius", r}, {"length", 0.7}}
                                 : json{{"type", "box"}, {"half_extents", {r, 0.35, r}}};
    return {{"bodies", {floorOf(static_cast<int>(draw.below(3))),
                        {{"name", "rod"}, {"mass", 0.1}, {"shape", shape}, {"position", {0, 0.6, 0}},
                         {"orientation", {0.7071067811865476, 0.7071067811865476, 0, 0}}}}}};
}

json farChildren(Draw &draw) {
    const double far[] = {1e3, 1e11, 9e11, 1e12, 2e12, 1e300};
    const double frame[] = {0, 9e11, -5e11};
    json children = {{{"shape", {{"type", "sphere"}, {"radius", 1}}}, {"position", {0, 0, 0}}},
                     {{"shape", {{"type", "box"}, {"half_extents", {1, 1, 1}}}}, {"position", {far[draw.below(6)], 0, 0}}}};
    return {{"bodies", {floorOf(2), {{"name", "c"}, {"shape", {{"type", "compound"}, {"children", children}}},
                                    {"position", {frame[draw.below(3)], 2, 0}}}}}};
}

TEST(Fuzz, HostileSceneKinds) {
    constexpr int kScenes = 120 / kScale;
    const double steps[] = {5e-324, 1e-310, 1e-7, 1e-6, 1e-3, 1.0 / 60};
    Draw draw(0x61);
    std::map<int, int> counts;
    Invocation invocation;
    invocation.command = Invocation::Command::Run;
    invocation.scene = "kind.json";
    invocation.steps = 30;
    invocation.quiet = true;
    for (int i = 0; i < kScenes; ++i) {
        json scene;
        switch (i % 4) {
        case 0: scene = rope(draw); break;
        case 1: scene = onePointSpawn(draw); break;
        case 2: scene = thinShape(draw); break;
        default: scene = farChildren(draw); break;
        }
        if (draw.chance(25)) scene["settings"] = {{"dt", steps[draw.below(std::size(steps))]}};
        const std::string text = scene.dump();
        std::ostringstream out, err;
        const int status = runSceneText(text, invocation, out, err, false);
        ++counts[status];
        ASSERT_TRUE(status == 0 || status == 2 || status == 3) << status << " for:\n" << text;
        if (status == 2) {
            ASSERT_TRUE(locatedRefusal(err.str(), "kind.json")) << "for:\n" << text;
        }
    }
    std::cout << "[ fuzz     ] " << kScenes << " hostile scene kinds:" << countsText(counts) << "\n";
    EXPECT_GT(counts[0], 0);
    EXPECT_GT(counts[2], 0);
}

// Inputs no mutation of a scene would reach.
TEST(Fuzz, PathologicalDocuments) {
    Invocation invocation;
    invocation.command = Invocation::Command::Run;
    invocation.scene = "odd.json";
    invocation.steps = 2;
    const std::string deep(100000, '[');
    const std::string cases[] = {
        deep + std::string(100000, ']'),
        "{\"bodies\": " + deep,
        std::string("\xef\xbb\xbf{\"bodies\": []}"),
        std::string("{\"bodies\": [], \"name\": \"\xff\xfe\"}"),
        std::string("{\"bodies\": []}\0garbage", 22),
        "{\"bodies\": [{\"name\": \"a\\nb\", \"shape\": {\"type\": \"sphere\", \"radius\": 1}, \"mass\": -1}]}",
        "{\"bodies\": [{\"name\": \"huge\", \"shape\": {\"type\": \"box\", \"half_extents\": [1e300, 1e300, 1e300]}}]}",
        "{\"bodies\": [{\"name\": \"far\", \"shape\": {\"type\": \"sphere\", \"radius\": 1}, \"position\": [1e300, -1e300, 1e300]}]}",
        "{\"bodies\": [{\"name\": \"tiny\", \"shape\": {\"type\": \"sphere\", \"radius\": 1e-300}, \"mass\": 1e-300}]}",
        "{\"settings\": {\"dt\": 1e300}, \"bodies\": [{\"name\": \"b\", \"shape\": {\"type\": \"sphere\", \"radius\": 1}}]}",
        "{\"settings\": {\"dt\": 5e-324}, \"bodies\": [{\"name\": \"b\", \"shape\": {\"type\": \"sphere\", \"radius\": 1}}]}",
    };
    for (const std::string &text : cases) {
        std::ostringstream out, err;
        const int status = runSceneText(text, invocation, out, err, false);
        EXPECT_TRUE(status == 0 || status == 2 || status == 3) << status << " for " << text.substr(0, 200);
        if (status == 2) {
            EXPECT_EQ(lineCount(err.str()), 1) << err.str();
        }
    }
    // Deep nesting is refused at once, with a path of bounded length.
    for (const std::string &text : {cases[0], cases[1]}) {
        std::ostringstream out, err;
        EXPECT_EQ(runSceneText(text, invocation, out, err, false), 2);
        EXPECT_NE(err.str().find("nested deeper than 64 levels"), std::string::npos) << err.str().substr(0, 300);
        EXPECT_LT(err.str().size(), 400u);
    }
}

}  // namespace
