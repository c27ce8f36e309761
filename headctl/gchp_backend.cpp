#include "headctl/gchp_backend.hpp"

#include "common/enum_names.hpp"

namespace gc::headctl {

namespace {
// Replies to requests abandoned after a timeout may still arrive; at most this many are skipped.
constexpr int kMaxStaleReplies = 64;

// The request that carries each kind of command.
constexpr EnumNames<CommandKind, 7, Command> kRequests{{
    {CommandKind::Absolute, Command::MoveAbsolute},
    {CommandKind::Relative, Command::MoveRelative},
    {CommandKind::Velocity, Command::MoveVelocity},
    {CommandKind::Stop, Command::Stop},
    {CommandKind::Home, Command::Home},
    {CommandKind::SavePreset, Command::PresetSave},
    {CommandKind::RecallPreset, Command::PresetRecall},
}};

// Only moves carry axis values.
bool is_move(CommandKind kind)
{
    return kind == CommandKind::Absolute || kind == CommandKind::Relative || kind == CommandKind::Velocity;
}

}  // namespace

GchpBackend::GchpBackend(std::string host, std::uint16_t port, std::string token)
    : host_(std::move(host)), port_(port), token_(std::move(token))
{
}

std::string GchpBackend::name() const { return "tcp://" + host_ + ":" + std::to_string(port_); }

void GchpBackend::open(Deadline deadline)
{
    close();
    fd_ = net::connect_to(host_, port_, net::Transport::Tcp, deadline);
    const auto line = reader_.read_line(fd_.get(), deadline);
    if (!line) throw net::NetError(name() + " sent no greeting in time");
    try {
        greeting_ = parse_greeting(*line);
    } catch (const ProtocolError& e) {
        // A refusal (too many clients) arrives instead of the greeting.
        if (line->rfind("ERR", 0) == 0) throw net::NetError(name() + " refused the connection: " + *line);
        throw net::NetError(name() + " sent a bad greeting: " + e.what());
    }
    if (greeting_.version != kProtocolVersion)
        throw net::NetError(name() + " speaks GCHP/" + std::to_string(greeting_.version) + ", expected GCHP/1");
    if (greeting_.caps.auth_required) {
        if (token_.empty()) throw net::NetError(name() + " requires a token");
        Request auth;
        auth.command = Command::Auth;
        auth.token = token_;
        const Reply r = transact(auth, deadline);
        // A head that has all the clients it serves says so only once the token is known.
        if (!r.ok && r.error == ErrorCode::Busy) throw net::NetError(name() + " refused the connection: " + r.message);
        if (!r.ok) throw net::NetError(name() + " refused the token: " + r.message);
    }
}

void GchpBackend::close()
{
    fd_.reset();
    reader_.clear();
}

Reply GchpBackend::transact(Request request, Deadline deadline)
{
    if (!fd_) throw net::NetError("not connected");
    request.id = next_id_++;
    const std::string line = format_request(request) + "\n";
    net::send_all(fd_.get(), std::span<const char>(line.data(), line.size()), deadline);
    for (int skipped = 0; skipped <= kMaxStaleReplies; ++skipped) {
        const auto text = reader_.read_line(fd_.get(), deadline);
        if (!text) throw net::NetError(name() + " did not answer in time");
        Reply reply;
        try {
            reply = parse_reply(*text);
        } catch (const ProtocolError& e) {
            throw net::NetError(name() + " sent a malformed reply: " + e.what());
        }
        if (reply.id == request.id) return reply;
    }
    throw net::NetError(name() + " sent too many replies to other requests");
}

HeadState GchpBackend::query_state(Deadline deadline)
{
    Request r;
    r.command = Command::Status;
    const Reply reply = transact(r, deadline);
    if (!reply.ok) throw HeadRejected("STATUS refused: " + reply.message);
    if (reply.body != ReplyBody::State) throw net::NetError(name() + " answered STATUS without a state");
    return reply.state;
}

std::optional<HeadLimits> GchpBackend::query_limits(Deadline deadline)
{
    Request r;
    r.command = Command::Limits;
    const Reply reply = transact(r, deadline);
    if (!reply.ok || reply.body != ReplyBody::Limits) return std::nullopt;
    return reply.limits;
}

void GchpBackend::send(const HeadCommand& command, Deadline deadline)
{
    Request r;
    r.command = name_in(kRequests, command.kind, Command::Stop);
    if (is_move(command.kind)) r.values = command.values;
    r.preset = command.preset;
    const Reply reply = transact(r, deadline);
    if (!reply.ok)
        throw HeadRejected(describe(command) + " refused (" + std::to_string(static_cast<int>(reply.error)) + " " +
                           std::string(error_code_name(reply.error)) + "): " + reply.message);
}

}  // namespace gc::headctl
