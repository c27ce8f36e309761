#include "headctl/soap_http.hpp"

#include <libsoup/soup.h>

namespace gc::headctl {

namespace {

constexpr gsize kReadChunk = 16 * 1024;

// The state of one POST while the main context runs its callbacks.
struct Transfer {
    GCancellable* cancel = g_cancellable_new();
    GInputStream* stream = nullptr;
    std::string body;
    std::size_t max_body = 0;
    std::string error;
    bool done = false;
    ~Transfer()
    {
        if (stream) g_object_unref(stream);
        g_object_unref(cancel);
    }
};

void finish(Transfer& t, GError* e)
{
    if (e) {
        t.error = e->message;
        g_error_free(e);
    }
    t.done = true;
}

void on_read(GObject* source, GAsyncResult* result, gpointer data)
{
    auto& t = *static_cast<Transfer*>(data);
    GError* e = nullptr;
    GBytes* bytes = g_input_stream_read_bytes_finish(G_INPUT_STREAM(source), result, &e);
    if (!bytes) return finish(t, e);
    gsize n = 0;
    const auto* chunk = static_cast<const char*>(g_bytes_get_data(bytes, &n));
    const bool fits = t.body.size() + n <= t.max_body;
    if (fits) t.body.append(chunk, n);
    g_bytes_unref(bytes);
    if (n == 0) return finish(t, nullptr);
    if (!fits) {
        t.error = "a reply longer than " + std::to_string(t.max_body) + " bytes";
        t.done = true;
        return;
    }
    g_input_stream_read_bytes_async(t.stream, kReadChunk, G_PRIORITY_DEFAULT, t.cancel, on_read, data);
}

void on_sent(GObject* source, GAsyncResult* result, gpointer data)
{
    auto& t = *static_cast<Transfer*>(data);
    GError* e = nullptr;
    t.stream = soup_session_send_finish(SOUP_SESSION(source), result, &e);
    if (!t.stream) return finish(t, e);
    g_input_stream_read_bytes_async(t.stream, kReadChunk, G_PRIORITY_DEFAULT, t.cancel, on_read, data);
}

// Pushes a main context as the thread's default for a scope: libsoup runs a session's
// callbacks on the context that was the default when the session was made.
class ContextScope {
public:
    explicit ContextScope(GMainContext* c) : c_(c) { g_main_context_push_thread_default(c_); }
    ~ContextScope() { g_main_context_pop_thread_default(c_); }
    ContextScope(const ContextScope&) = delete;
    ContextScope& operator=(const ContextScope&) = delete;

private:
    GMainContext* c_;
};

}  // namespace

SoapHttpClient::SoapHttpClient(std::string url) : url_(std::move(url)), context_(g_main_context_new()) {}

SoapHttpClient::~SoapHttpClient()
{
    reset();
    g_main_context_unref(context_);
}

void SoapHttpClient::reset()
{
    if (!session_) return;
    ContextScope scope(context_);
    soup_session_abort(session_);
    g_object_unref(session_);
    session_ = nullptr;
}

HttpReply SoapHttpClient::post(std::string_view body, std::string_view action, net::Clock::time_point deadline,
                               std::size_t max_reply)
{
    ContextScope scope(context_);
    // No proxy: a head is addressed directly, whatever the environment says.
    if (!session_)
        session_ = soup_session_new_with_options("proxy-resolver", nullptr, "max-conns", 2, "max-conns-per-host", 1,
                                                 "user-agent", "gesturecam-headctl", nullptr);
    SoupMessage* message = soup_message_new("POST", url_.c_str());
    if (!message) throw net::NetError("cannot make an HTTP request of " + url_);
    const std::string type = "application/soap+xml; charset=utf-8; action=\"" + std::string(action) + "\"";
    GBytes* bytes = g_bytes_new(body.data(), body.size());
    soup_message_set_request_body_from_bytes(message, type.c_str(), bytes);
    g_bytes_unref(bytes);

    Transfer t;
    t.max_body = max_reply;
    soup_session_send_async(session_, message, G_PRIORITY_DEFAULT, t.cancel, on_sent, &t);
    bool timed_out = false, cancelled = false;
    while (!t.done) {
        if (!timed_out && !cancelled && (net::Clock::now() >= deadline || net::cancel_requested())) {
            (net::Clock::now() >= deadline ? timed_out : cancelled) = true;
            g_cancellable_cancel(t.cancel);
        }
        // Wakes at least every 20 ms to look at the deadline and the cancel flag.
        GSource* tick = g_timeout_source_new(20);
        g_source_set_callback(
            tick, [](gpointer) { return G_SOURCE_REMOVE; }, nullptr, nullptr);
        g_source_attach(tick, context_);
        g_main_context_iteration(context_, TRUE);
        g_source_destroy(tick);
        g_source_unref(tick);
    }
    HttpReply reply{soup_message_get_status(message), std::move(t.body)};
    g_object_unref(message);
    if (timed_out || cancelled || !t.error.empty()) {
        // What is left of the exchange is of no use: the connection goes with it.
        if (t.stream) {
            g_object_unref(t.stream);
            t.stream = nullptr;
        }
        soup_session_abort(session_);
        if (cancelled) throw net::NetError("cancelled");
        if (timed_out) throw net::NetError(url_ + " did not answer in time");
        throw net::NetError(url_ + ": " + t.error);
    }
    return reply;
}

}  // namespace gc::headctl
