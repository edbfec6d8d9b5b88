#include "atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace cyclone::scene {

namespace {

std::string reason() { return errno ? std::strerror(errno) : "write error"; }

}  // namespace

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), temporary_(path_ + ".tmp-" + std::to_string(::getpid())) {
    errno = 0;
    out_.open(temporary_, std::ios::binary | std::ios::trunc);
    if (!out_) throw std::runtime_error("cannot write " + path_ + ": " + reason());
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        out_.close();
        std::remove(temporary_.c_str());
    }
}

void AtomicFile::commit() {
    errno = 0;
    out_.flush();
    const bool written = static_cast<bool>(out_);
    out_.close();
    if (!written || !out_) throw std::runtime_error("cannot write " + path_ + ": " + reason());
    if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
        throw std::runtime_error("cannot write " + path_ + ": " + reason());
    }
    committed_ = true;
}

}  // namespace cyclone::scene
