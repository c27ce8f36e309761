#include "headctl/sim/onvif_responder.hpp"

#include "headctl/head_backend.hpp"
#include "headctl/token.hpp"

#include <libsoup/soup.h>
#include <sys/socket.h>

#include <charconv>
#include <stdexcept>

namespace gc::headctl {

namespace {

// A request the head refuses: the SOAP fault and its HTTP status (400 for the sender's
// faults, 500 for the receiver's, as SOAP 1.2's HTTP binding has it).
struct Refusal {
    onvif::Fault fault;
    unsigned status = 400;
};

[[noreturn]] void refuse(const char* subcode, const std::string& reason) { throw Refusal{{"Sender", subcode, reason}}; }

double checked(double generic, double lo, double hi, const char* what)
{
    if (!(generic >= lo && generic <= hi))
        refuse("InvalidArgVal", std::string(what) + " lies outside the generic space");
    return generic;
}

int preset_number(const std::string& token)
{
    int n = -1;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), n);
    if (token.empty() || ec != std::errc{} || ptr != token.data() + token.size() || n < 0 || n > kMaxPreset)
        refuse("NoToken", "preset tokens here are the numbers 0.." + std::to_string(kMaxPreset));
    return n;
}

onvif::PtzStatus status_of(HeadModel& m, double now)
{
    const HeadState s = m.state(now);
    const HeadLimits& l = m.limits();
    onvif::PtzStatus out;
    out.pan_tilt = {onvif::to_generic(s.pose.pan_deg, l[Axis::Pan].min_deg, l[Axis::Pan].max_deg),
                    onvif::to_generic(s.pose.tilt_deg, l[Axis::Tilt].min_deg, l[Axis::Tilt].max_deg)};
    const double zoom_max = l[Axis::Zoom].max_deg;
    out.zoom = zoom_max > 1.0 ? onvif::zoom_to_generic(s.pose.zoom, zoom_max) : 0.0;
    out.pan_tilt_moving = s.moving_axis(Axis::Pan) || s.moving_axis(Axis::Tilt);
    out.zoom_moving = s.moving_axis(Axis::Zoom);
    return out;
}

// The axes of an AbsoluteMove (positions) or ContinuousMove (velocities) in the head's units.
AxisValues head_values(const onvif::PtzRequest& r, const HeadLimits& l, bool velocity)
{
    AxisValues v;
    if (r.pan_tilt) {
        const double x = checked(r.pan_tilt->x, -1, 1, "PanTilt x");
        const double y = checked(r.pan_tilt->y, -1, 1, "PanTilt y");
        v.set(Axis::Pan, velocity ? x * l[Axis::Pan].max_velocity_dps
                                  : onvif::from_generic(x, l[Axis::Pan].min_deg, l[Axis::Pan].max_deg));
        v.set(Axis::Tilt, velocity ? y * l[Axis::Tilt].max_velocity_dps
                                   : onvif::from_generic(y, l[Axis::Tilt].min_deg, l[Axis::Tilt].max_deg));
    }
    if (r.zoom) {
        const double z = checked(*r.zoom, velocity ? -1 : 0, 1, "Zoom x");
        v.set(Axis::Zoom,
              velocity ? z * l[Axis::Zoom].max_velocity_dps : onvif::zoom_from_generic(z, l[Axis::Zoom].max_deg));
    }
    if (v.empty()) refuse("InvalidArgVal", r.operation + " names no axis");
    return v;
}

std::string presets_of(const HeadModel& m)
{
    std::vector<onvif::Preset> presets;
    for (int n : m.preset_numbers()) presets.push_back({std::to_string(n), "preset " + std::to_string(n)});
    return onvif::presets_response(presets);
}

std::string save_preset(HeadModel& m, double now, const std::string& token)
{
    int n = 0;
    if (token.empty()) {  // the lowest number not yet taken
        for (int taken : m.preset_numbers()) n += taken == n ? 1 : 0;
        if (n > kMaxPreset) refuse("TooManyPresets", "every preset number is taken");
    } else {
        n = preset_number(token);
    }
    m.save_preset(n, now);
    return onvif::set_preset_response(std::to_string(n));
}

// The operation on the head and its response; throws Refusal.
std::string operate(HeadModel& m, double now, const onvif::PtzRequest& r)
{
    const std::string& op = r.operation;
    if (op == "GetStatus") return onvif::status_response(status_of(m, now));
    if (op == "GetPresets") return presets_of(m);
    if (op == "SetPreset") return save_preset(m, now, r.preset_token);
    if (op == "AbsoluteMove")
        m.move_absolute(head_values(r, m.limits(), false), now);
    else if (op == "ContinuousMove")
        m.move_velocity(head_values(r, m.limits(), true), now);
    else if (op == "Stop")
        m.stop(now);
    else if (op == "GotoHomePosition")
        m.home(now);
    else if (op == "GotoPreset")
        m.recall_preset(preset_number(r.preset_token), now);
    else
        throw Refusal{{"Receiver", "ActionNotSupported", "the PTZ service has no operation " + op.substr(0, 64)}, 500};
    return onvif::empty_response(op);
}

std::string peer_key(SoupServerMessage* message)
{
    sockaddr_storage peer{};
    GSocketAddress* address = soup_server_message_get_remote_address(message);
    if (!address || !g_socket_address_to_native(address, &peer, sizeof peer, nullptr)) return "?";
    return address_key(peer);
}

gboolean quit_loop(gpointer loop)
{
    g_main_loop_quit(static_cast<GMainLoop*>(loop));
    return G_SOURCE_REMOVE;
}

}  // namespace

OnvifResponder::OnvifResponder(const OnvifResponderConfig& config, HeadServer& head)
    : config_(config), head_(head), throttle_(config.auth_delay_initial, config.auth_delay_max),
      context_(g_main_context_new()), loop_(g_main_loop_new(context_, FALSE))
{
    try {
        listen();
    } catch (...) {
        release();
        throw;
    }
    thread_ = std::thread([this] {
        g_main_context_push_thread_default(context_);
        g_main_loop_run(loop_);
        g_main_context_pop_thread_default(context_);
    });
}

void OnvifResponder::listen()
{
    if (!config_.password.empty()) check_token(config_.password);
    if (config_.idle_timeout.count() <= 0) throw std::invalid_argument("the ONVIF idle timeout must be > 0");
    if (config_.password.empty() && !config_.allow_remote_without_password && !is_loopback_address(config_.host))
        throw std::invalid_argument("refusing to serve ONVIF on " + config_.host +
                                    " without a password: anyone who reaches it could move the head");
    GInetAddress* inet = g_inet_address_new_from_string(config_.host.c_str());
    if (!inet)
        throw std::invalid_argument("ONVIF address '" + config_.host + "' is not a numeric IPv4 or IPv6 address");
    GSocketAddress* address = g_inet_socket_address_new(inet, config_.port);
    g_object_unref(inet);
    g_main_context_push_thread_default(context_);
    server_ = soup_server_new("server-header", "gesturecam-headsim", nullptr);
    g_signal_connect(server_, "request-started", G_CALLBACK(on_request_started), this);
    soup_server_add_handler(server_, nullptr, reinterpret_cast<SoupServerCallback>(on_request), this, nullptr);
    GError* error = nullptr;
    const bool listening = soup_server_listen(server_, address, static_cast<SoupServerListenOptions>(0), &error);
    g_object_unref(address);
    g_main_context_pop_thread_default(context_);
    if (!listening) {
        const std::string why = error ? error->message : "unknown error";
        g_clear_error(&error);
        throw std::runtime_error("cannot bind ONVIF " + config_.host + ":" + std::to_string(config_.port) + ": " + why);
    }
    GSList* uris = soup_server_get_uris(server_);
    if (uris) port_ = static_cast<std::uint16_t>(g_uri_get_port(static_cast<GUri*>(uris->data)));
    g_slist_free_full(uris, reinterpret_cast<GDestroyNotify>(g_uri_unref));
}

void OnvifResponder::release()
{
    if (server_) {
        g_main_context_push_thread_default(context_);
        soup_server_disconnect(server_);
        g_object_unref(server_);
        g_main_context_pop_thread_default(context_);
        server_ = nullptr;
    }
    if (loop_) g_main_loop_unref(loop_);
    if (context_) g_main_context_unref(context_);
    loop_ = nullptr;
    context_ = nullptr;
}

OnvifResponder::~OnvifResponder()
{
    // An idle source quits the loop even if it has not started running yet.
    g_main_context_invoke(context_, quit_loop, loop_);
    if (thread_.joinable()) thread_.join();
    release();
}

void OnvifResponder::on_request_started(SoupServer*, SoupServerMessage* message, void* self)
{
    auto* responder = static_cast<OnvifResponder*>(self);
    // The socket's timeout ends a connection that stalls while a request is read or written.
    if (GSocket* socket = soup_server_message_get_socket(message))
        g_socket_set_timeout(socket, static_cast<guint>(responder->config_.idle_timeout.count()));
    g_signal_connect(message, "got-headers", G_CALLBACK(on_got_headers), self);
    g_signal_connect(message, "got-chunk", G_CALLBACK(on_got_chunk), self);
}

namespace {

// Closes the connection of a request over the size limit: libsoup would read its body whole.
void cut_off(SoupServerMessage* message)
{
    if (GSocket* socket = soup_server_message_get_socket(message)) g_socket_shutdown(socket, TRUE, TRUE, nullptr);
}

}  // namespace

void OnvifResponder::on_got_headers(SoupServerMessage* message, void*)
{
    SoupMessageHeaders* headers = soup_server_message_get_request_headers(message);
    if (soup_message_headers_get_encoding(headers) == SOUP_ENCODING_CONTENT_LENGTH &&
        soup_message_headers_get_content_length(headers) > static_cast<goffset>(onvif::kMaxMessageBytes))
        cut_off(message);
}

void OnvifResponder::on_got_chunk(SoupServerMessage* message, void*, void*)
{
    if (soup_server_message_get_request_body(message)->length > static_cast<goffset>(onvif::kMaxMessageBytes))
        cut_off(message);
}

void OnvifResponder::on_request(SoupServer*, SoupServerMessage* message, const char*, void*, void* self)
{
    if (std::string_view(soup_server_message_get_method(message)) != "POST") {
        soup_server_message_set_status(message, SOUP_STATUS_METHOD_NOT_ALLOWED, nullptr);
        return;
    }
    GBytes* body = soup_message_body_flatten(soup_server_message_get_request_body(message));
    gsize size = 0;
    const auto* data = static_cast<const char*>(g_bytes_get_data(body, &size));
    const auto [status, reply] =
        static_cast<OnvifResponder*>(self)->answer(std::string_view(data ? data : "", size), peer_key(message));
    g_bytes_unref(body);
    soup_server_message_set_response(message, "application/soap+xml; charset=utf-8", SOUP_MEMORY_COPY, reply.data(),
                                     reply.size());
    soup_server_message_set_status(message, status, nullptr);
}

std::pair<unsigned, std::string> OnvifResponder::answer(std::string_view body, const std::string& address)
{
    try {
        onvif::Envelope envelope;
        try {
            envelope = onvif::parse_envelope(body);
        } catch (const onvif::SoapError& e) {
            refuse("WellFormed", e.what());
        }
        if (!config_.password.empty())
            if (const std::string why = authentication_error(envelope, address); !why.empty())
                refuse("NotAuthorized", why);
        onvif::PtzRequest request;
        try {
            request = onvif::parse_request(envelope);
        } catch (const onvif::SoapError& e) {
            refuse("InvalidArgVal", e.what());
        }
        return {SOUP_STATUS_OK, perform(request)};
    } catch (const Refusal& r) {
        return {r.status, onvif::fault_envelope(r.fault)};
    }
}

std::string OnvifResponder::authentication_error(const onvif::Envelope& envelope, const std::string& address)
{
    std::lock_guard lock(throttle_mutex_);
    const auto now = AuthThrottle::Clock::now();
    if (now < throttle_.next_check(address)) return "too many wrong credentials from this address: try again later";
    bool ok = false;
    try {
        const auto token = onvif::username_token(envelope);
        if (!token) return "a WS-Security UsernameToken with a password digest is required";
        const std::string expected = onvif::password_digest(token->nonce, token->created, config_.password);
        // Both compared whatever the first gives, so timing does not tell a known user.
        const bool user_ok = same_secret(token->user, config_.user);
        const bool digest_ok = same_secret(token->digest, expected);
        ok = user_ok && digest_ok;
    } catch (const onvif::SoapError&) {
        ok = false;
    }
    if (!ok) {
        throttle_.failed(address, now);
        return "wrong user name or password";
    }
    throttle_.succeeded(address);
    return {};
}

std::string OnvifResponder::perform(const onvif::PtzRequest& request)
{
    std::string response;
    try {
        head_.with_model([&](HeadModel& model, double now) { response = operate(model, now, request); });
    } catch (const std::out_of_range& e) {
        refuse(request.operation == "GotoPreset" ? "NoToken" : "InvalidArgVal", e.what());
    }
    return response;
}

}  // namespace gc::headctl
