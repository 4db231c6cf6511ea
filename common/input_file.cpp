#include "common/input_file.h"

#include "common/error.h"

#include <algorithm>
#include <cerrno>
#include <fcntl.h>
#include <mutex>
#include <sys/stat.h>
#include <unistd.h>

namespace sward {

namespace {

std::string limitText(uint64_t bytes) {
    if (bytes >= (uint64_t(1) << 20) && bytes % (uint64_t(1) << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes) + " bytes";
}

// Reads the open file's `size` bytes into `out` (a std::string or a byte vector).
template <class Bytes> Bytes readWhole(const std::string& path, const std::string& what, uint64_t maxBytes) {
    const InputFile file = openInputFile(path, what);
    // Checked before reading, so a huge file is refused without being loaded.
    if (file.size() > maxBytes)
        throw Error(path + ": the " + what + " has " + std::to_string(file.size()) + " bytes, over the limit of " +
                    limitText(maxBytes));
    Bytes bytes(size_t(file.size()), 0);
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::read(file.fd(), bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw Error(path + ": cannot read the " + what + (n == 0 ? " (it shrank while read)" : ""));
        done += size_t(n);
    }
    return bytes;
}

} // namespace

InputFile::InputFile(InputFile&& other) noexcept : fd_(other.fd_), size_(other.size_) {
    other.fd_ = -1;
}

InputFile& InputFile::operator=(InputFile&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = other.fd_;
        size_ = other.size_;
        other.fd_ = -1;
    }
    return *this;
}

InputFile::~InputFile() {
    if (fd_ >= 0) ::close(fd_);
}

InputFile openInputFile(const std::string& path, const std::string& what) {
    // O_NONBLOCK: opening a FIFO for reading would wait for a writer; the fstat below then refuses it.
    InputFile file;
    file.fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (file.fd_ < 0) throw Error(path + ": cannot open the " + what + " (missing or unreadable)");
    struct stat info {};
    if (::fstat(file.fd_, &info) != 0) throw Error(path + ": cannot open the " + what + " (missing or unreadable)");
    if (!S_ISREG(info.st_mode)) throw Error(path + ": the " + what + " is not a regular file");
    file.size_ = uint64_t(info.st_size);
    return file;
}

std::string readInputFile(const std::string& path, const std::string& what, uint64_t maxBytes) {
    return readWhole<std::string>(path, what, maxBytes);
}

std::vector<unsigned char> readInputBytes(const std::string& path, const std::string& what, uint64_t maxBytes) {
    return readWhole<std::vector<unsigned char>>(path, what, maxBytes);
}

struct InputFolders::Log {
    std::mutex mutex;
    std::vector<OpenedInput> files;
};

InputFolders::InputFolders() : log_(std::make_shared<Log>()) {}

InputFolders InputFolders::confinedTo(std::vector<std::filesystem::path> folders) {
    InputFolders result;
    result.confined_ = true;
    result.folders_ = std::move(folders);
    return result;
}

bool InputFolders::allows(const std::filesystem::path& real) const {
    if (!confined_) return true;
    return std::any_of(folders_.begin(), folders_.end(), [&](const std::filesystem::path& folder) {
        auto p = real.begin();
        for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
            if (f->empty()) continue; // a trailing separator
            if (p == real.end() || *p != *f) return false;
        }
        return true;
    });
}

void InputFolders::record(const std::string& owner, const std::string& path) const {
    std::lock_guard lock(log_->mutex);
    const OpenedInput entry{owner, path};
    if (std::find(log_->files.begin(), log_->files.end(), entry) == log_->files.end()) log_->files.push_back(entry);
}

std::vector<OpenedInput> InputFolders::opened() const {
    std::lock_guard lock(log_->mutex);
    return log_->files;
}

} // namespace sward
