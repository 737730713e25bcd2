#include "protocol.h"

#include <climits>
#include <cstring>

namespace strahl::distributed {

void sendBytes(std::span<const std::byte> bytes, int destination, Tag tag) {
    if (bytes.size() > size_t(INT_MAX))
        fail("a message of ", bytes.size(), " bytes is larger than MPI's limit of ", INT_MAX,
             " (use a smaller --tile)");
    // MPI_Send takes a non-const pointer only in MPI-2 headers; Open MPI 4 has const.
    MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, destination, tag,
             MPI_COMM_WORLD);
}

void sendText(const std::string& text, int destination, Tag tag) {
    sendBytes(std::as_bytes(std::span<const char>(text.data(), text.size())), destination, tag);
}

void AsyncSends::send(std::vector<std::byte> bytes, int destination, Tag tag) {
    if (bytes.size() > size_t(INT_MAX))
        fail("a message of ", bytes.size(), " bytes is larger than MPI's limit of ", INT_MAX,
             " (use a smaller --tile)");
    pending_.push_back({MPI_REQUEST_NULL, std::move(bytes)});
    Pending& p = pending_.back();  // deque: stays where it is while others are added
    MPI_Isend(p.bytes.data(), static_cast<int>(p.bytes.size()), MPI_BYTE, destination, tag,
              MPI_COMM_WORLD, &p.request);
}

void AsyncSends::progress() {
    while (!pending_.empty()) {
        int done = 0;
        MPI_Test(&pending_.front().request, &done, MPI_STATUS_IGNORE);
        if (!done) return;
        pending_.pop_front();
    }
}

void AsyncSends::finish() {
    for (Pending& p : pending_) MPI_Wait(&p.request, MPI_STATUS_IGNORE);
    pending_.clear();
}

namespace {

Message receiveMatched(MPI_Message& handle, const MPI_Status& status) {
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    Message message;
    message.source = status.MPI_SOURCE;
    message.tag = status.MPI_TAG;
    message.bytes.resize(static_cast<size_t>(count));
    MPI_Mrecv(message.bytes.data(), count, MPI_BYTE, &handle, MPI_STATUS_IGNORE);
    return message;
}

}  // namespace

std::optional<Message> tryReceive() {
    int found = 0;
    MPI_Message handle;
    MPI_Status status;
    MPI_Improbe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &found, &handle, &status);
    if (!found) return std::nullopt;
    return receiveMatched(handle, status);
}

Message receive(int source, Tag tag) {
    MPI_Message handle;
    MPI_Status status;
    MPI_Mprobe(source, tag, MPI_COMM_WORLD, &handle, &status);
    return receiveMatched(handle, status);
}

std::vector<std::byte> encodeAssignment(const std::vector<TileWork>& tiles) {
    std::vector<std::byte> message;
    for (const TileWork& work : tiles) {
        TileHeader header;
        header.tile = work.tile;
        header.passEnd = work.passEnd;
        header.bytes = work.state.size();
        const auto head = asBytes(header);
        message.insert(message.end(), head.begin(), head.end());
        message.insert(message.end(), work.state.begin(), work.state.end());
    }
    return message;
}

std::vector<TileWork> decodeAssignment(std::span<const std::byte> bytes, size_t tileCount) {
    std::vector<TileWork> tiles;
    for (size_t at = 0; at < bytes.size();) {
        TileHeader header;
        if (bytes.size() - at < sizeof header)
            fail("the scheduler sent a truncated tile assignment");
        std::memcpy(&header, bytes.data() + at, sizeof header);
        at += sizeof header;
        if (bytes.size() - at < header.bytes) fail("the scheduler sent a truncated tile assignment");
        if (header.tile < 0 || static_cast<size_t>(header.tile) >= tileCount || header.passEnd < 1)
            fail("the scheduler assigned tile ", header.tile, " up to pass ", header.passEnd,
                 " of an image cut into ", tileCount, " tiles");
        TileWork work;
        work.tile = header.tile;
        work.passEnd = header.passEnd;
        work.state.assign(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                          bytes.begin() + static_cast<std::ptrdiff_t>(at + header.bytes));
        at += header.bytes;
        tiles.push_back(std::move(work));
    }
    return tiles;
}

std::string asText(const Message& message) {
    return std::string(reinterpret_cast<const char*>(message.bytes.data()), message.bytes.size());
}

}  // namespace strahl::distributed
