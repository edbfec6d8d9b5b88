// What the runner reads and writes: outputs that name one file however they are spelled
// are refused before anything is written, and the scene is read with a bound on the read
// itself, whatever kind of file it is.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "cli.h"
#include "scene_loader.h"
#include "runner_test_support.h"

namespace {

using namespace runner_test;

// One spelling per way two names reach one file: a "." step, a ".." over a folder that
// does not exist (weakly_canonical resolves it lexically), a symbolic link to the folder,
// and a hard link to an existing file.
TEST(OutputFiles, OneFileUnderTwoSpellingsIsRefusedAndKeepsItsContent) {
    TempDir dir;
    const std::string out = dir.file("out.json");
    fs::create_directory_symlink(dir.file(""), dir.file("alias"));
    writeText(out, "keep");
    fs::create_hard_link(out, dir.file("hard.json"));
    const std::string spellings[] = {dir.file("./out.json"), dir.file("missing/../out.json"),
                                     dir.file("alias/out.json"), dir.file("hard.json")};
    for (const std::string &trace : spellings) {
        const Process p = runWorld({"run", scenePath("tower"), "--steps", "5", "--summary", out, "--trace", trace}, dir);
        EXPECT_EQ(p.status, 2) << trace;
        EXPECT_EQ(lineCount(p.err), 1) << p.err;
        EXPECT_NE(p.err.find("--summary " + out + " and --trace " + trace + " name the same file"), std::string::npos)
            << p.err;
        EXPECT_TRUE(p.out.empty());
        EXPECT_EQ(readText(out), "keep") << trace;
        EXPECT_EQ(dir.files().size(), 3u) << trace;  // out.json, hard.json, alias: no temporary left
    }
}

TEST(OutputFiles, AnOutputOverTheSceneOrAFolderIsRefused) {
    TempDir dir;
    const std::string scene = dir.file("scene.json");
    const std::string text = readText(scenePath("tower"));
    writeText(scene, text);
    fs::create_directory(dir.file("folder"));
    struct Case {
        std::vector<std::string> args;
        std::string message;
    } cases[] = {
        {{"--summary", dir.file("./scene.json")}, "--summary " + dir.file("./scene.json") + " is the scene file"},
        {{"--trace", scene}, "--trace " + scene + " is the scene file"},
        {{"--summary", dir.file("folder")}, "--summary " + dir.file("folder") + " is a directory"},
    };
    for (const Case &c : cases) {
        std::vector<std::string> args = {"run", scene, "--steps", "5"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        const Process p = runWorld(args, dir);
        EXPECT_EQ(p.status, 2) << c.message;
        EXPECT_EQ(lineCount(p.err), 1) << p.err;
        EXPECT_NE(p.err.find(c.message), std::string::npos) << p.err;
        EXPECT_EQ(readText(scene), text);
        EXPECT_TRUE(fs::is_empty(dir.file("folder")));
        EXPECT_EQ(dir.files().size(), 2u);
    }
}

// /dev/zero has no size to check and never ends; its first byte is a NUL, which no JSON
// text holds, so the read stops there and the parser places the error.
TEST(SceneFile, DevZeroIsRefusedAtOnce) {
    TempDir dir;
    const auto start = std::chrono::steady_clock::now();
    const Process p = runWorld({"run", "/dev/zero", "--summary", dir.file("s.json")}, dir);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(p.status, 2);
    EXPECT_EQ(lineCount(p.err), 1) << p.err;
    EXPECT_EQ(p.err, "/dev/zero: (top level): invalid JSON: a NUL byte at offset 0, which no JSON text holds\n");
    EXPECT_LT(seconds, 10.0);
    EXPECT_TRUE(dir.files().empty());
}

TEST(SceneFile, ReadStopsAfterTheFirstNulByte) {
    TempDir dir;
    writeText(dir.file("nul.json"), std::string("{\"bodies\": []}\0garbage", 22));
    EXPECT_EQ(cyclone::scene::readSceneFile(dir.file("nul.json")), std::string("{\"bodies\": []}\0", 15));
}

TEST(SceneFile, ANulByteIsPlacedWhereItSits) {
    try {
        cyclone::scene::loadScene(std::string("{\"bodies\": [\0]}", 15), "x");
        FAIL() << "accepted a NUL byte";
    } catch (const cyclone::scene::SceneError &error) {
        EXPECT_EQ(error.path(), "bodies[0]");
        EXPECT_EQ(error.message(), "invalid JSON: a NUL byte at offset 12, which no JSON text holds");
    }
}

void expectTooLarge(const std::string &path, std::uintmax_t limit) {
    try {
        cyclone::scene::readSceneFile(path, limit);
        FAIL() << "read " << path << " beyond " << limit << " bytes";
    } catch (const std::runtime_error &error) {
        EXPECT_EQ(std::string(error.what()), "cannot read: larger than " + std::to_string(limit) + " bytes");
    }
}

TEST(SceneFile, ARegularFileBeyondTheLimitIsRefused) {
    TempDir dir;
    writeText(dir.file("big.json"), std::string(5000, ' '));
    expectTooLarge(dir.file("big.json"), 4096);
    EXPECT_EQ(cyclone::scene::readSceneFile(dir.file("big.json"), 5000).size(), 5000u);
}

// A pipe has no size in stat(): only the bounded read itself can refuse it. 8 KiB fit in
// the pipe's buffer, so the writer finishes whether or not the reader reads them all.
TEST(SceneFile, APipeBeyondTheLimitIsRefused) {
    TempDir dir;
    const std::string fifo = dir.file("pipe");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] {
        const int fd = ::open(fifo.c_str(), O_WRONLY);
        if (fd < 0) return;
        const std::string spaces(8192, ' ');
        [[maybe_unused]] const auto written = ::write(fd, spaces.data(), spaces.size());
        ::close(fd);
    });
    expectTooLarge(fifo, 4096);
    writer.join();
}

}  // namespace
