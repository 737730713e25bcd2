#include "protocol.h"

#include <climits>

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

std::string asText(const Message& message) {
    return std::string(reinterpret_cast<const char*>(message.bytes.data()), message.bytes.size());
}

}  // namespace strahl::distributed
