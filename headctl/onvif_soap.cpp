#include "headctl/onvif_soap.hpp"

#include <glib.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <sys/random.h>

#include <cmath>
#include <memory>
#include <mutex>

namespace gc::headctl::onvif {

namespace {

constexpr std::string_view kSoapNs = "http://www.w3.org/2003/05/soap-envelope";
constexpr std::string_view kPtzNs = "http://www.onvif.org/ver20/ptz/wsdl";
constexpr std::string_view kSchemaNs = "http://www.onvif.org/ver10/schema";
constexpr std::string_view kErrorNs = "http://www.onvif.org/ver10/error";
constexpr std::string_view kWsseNs =
    "http://docs.oasis-open.org/wss/2004/01/oasis-200401-wss-wssecurity-secext-1.0.xsd";
constexpr std::string_view kWsuNs =
    "http://docs.oasis-open.org/wss/2004/01/oasis-200401-wss-wssecurity-utility-1.0.xsd";
constexpr std::string_view kDigestType =
    "http://docs.oasis-open.org/wss/2004/01/oasis-200401-wss-username-token-profile-1.0#PasswordDigest";
constexpr std::string_view kBase64Type =
    "http://docs.oasis-open.org/wss/2004/01/oasis-200401-wss-soap-message-security-1.0#Base64Binary";
constexpr std::string_view kPositionPanTilt = "http://www.onvif.org/ver10/tptz/PanTiltSpaces/PositionGenericSpace";
constexpr std::string_view kPositionZoom = "http://www.onvif.org/ver10/tptz/ZoomSpaces/PositionGenericSpace";
constexpr std::string_view kVelocityPanTilt = "http://www.onvif.org/ver10/tptz/PanTiltSpaces/VelocityGenericSpace";
constexpr std::string_view kVelocityZoom = "http://www.onvif.org/ver10/tptz/ZoomSpaces/VelocityGenericSpace";
constexpr int kMaxDepth = 32;
constexpr int kMaxElements = 2048;

struct DocFree {
    void operator()(xmlDoc* d) const { xmlFreeDoc(d); }
};

std::string escaped(std::string_view text)
{
    gchar* e = g_markup_escape_text(text.data(), static_cast<gssize>(text.size()));
    std::string out(e);
    g_free(e);
    return out;
}

std::string number(double v)
{
    char b[G_ASCII_DTOSTR_BUF_SIZE];
    return g_ascii_formatd(b, sizeof b, "%.6f", v);
}

double parse_number(const std::optional<std::string>& text, const char* what)
{
    if (!text || text->empty()) throw SoapError(std::string("missing ") + what);
    char* end = nullptr;
    const double v = g_ascii_strtod(text->c_str(), &end);
    if (end != text->c_str() + text->size() || !std::isfinite(v)) throw SoapError(std::string("bad number in ") + what);
    return v;
}

const char* local_name(const xmlNode* n) { return reinterpret_cast<const char*>(n->name); }

void convert(const xmlNode* node, XmlElement& out, int depth, int& count)
{
    if (depth > kMaxDepth || ++count > kMaxElements) throw SoapError("message nested too deeply or too large");
    out.name = local_name(node);
    for (const xmlAttr* a = node->properties; a; a = a->next) {
        xmlChar* v = xmlNodeListGetString(node->doc, a->children, 1);
        out.attributes.emplace_back(local_name(reinterpret_cast<const xmlNode*>(a)),
                                    v ? reinterpret_cast<char*>(v) : "");
        xmlFree(v);
    }
    for (const xmlNode* c = node->children; c; c = c->next) {
        if (c->type == XML_ELEMENT_NODE) {
            out.children.emplace_back();
            convert(c, out.children.back(), depth + 1, count);
        } else if ((c->type == XML_TEXT_NODE || c->type == XML_CDATA_SECTION_NODE) && c->content) {
            out.text += reinterpret_cast<const char*>(c->content);
        }
    }
}

std::string trimmed(std::string_view s)
{
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string_view::npos) return {};
    return std::string(s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1));
}

const XmlElement& need(const XmlElement* e, const char* what)
{
    if (!e) throw SoapError(std::string("missing ") + what);
    return *e;
}

std::string envelope_text(std::string_view header, std::string_view body)
{
    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<s:Envelope xmlns:s=\"";
    out.append(kSoapNs).append("\" xmlns:tptz=\"").append(kPtzNs).append("\" xmlns:tt=\"").append(kSchemaNs);
    out.append("\" xmlns:ter=\"").append(kErrorNs).append("\">");
    if (!header.empty()) out.append("<s:Header>").append(header).append("</s:Header>");
    return out.append("<s:Body>").append(body).append("</s:Body></s:Envelope>\n");
}

std::string security_header(const UsernameToken& t)
{
    std::string out = "<wsse:Security s:mustUnderstand=\"1\" xmlns:wsse=\"";
    out.append(kWsseNs).append("\" xmlns:wsu=\"").append(kWsuNs).append("\"><wsse:UsernameToken><wsse:Username>");
    out.append(escaped(t.user)).append("</wsse:Username><wsse:Password Type=\"").append(kDigestType).append("\">");
    out.append(escaped(t.digest)).append("</wsse:Password><wsse:Nonce EncodingType=\"").append(kBase64Type);
    out.append("\">").append(escaped(t.nonce)).append("</wsse:Nonce><wsu:Created>").append(escaped(t.created));
    return out.append("</wsu:Created></wsse:UsernameToken></wsse:Security>");
}

std::string pan_tilt_element(const PanTilt& p, std::string_view space)
{
    return "<tt:PanTilt x=\"" + number(p.x) + "\" y=\"" + number(p.y) + "\" space=\"" + std::string(space) + "\"/>";
}

std::string zoom_element(double z, std::string_view space)
{
    return "<tt:Zoom x=\"" + number(z) + "\" space=\"" + std::string(space) + "\"/>";
}

std::string element(std::string_view name, std::string_view text)
{
    return "<tptz:" + std::string(name) + ">" + escaped(text) + "</tptz:" + std::string(name) + ">";
}

// The vector (Position or Velocity) of an AbsoluteMove or ContinuousMove.
std::string vector_element(const PtzRequest& r, bool velocity)
{
    std::string inner;
    if (r.pan_tilt) inner += pan_tilt_element(*r.pan_tilt, velocity ? kVelocityPanTilt : kPositionPanTilt);
    if (r.zoom) inner += zoom_element(*r.zoom, velocity ? kVelocityZoom : kPositionZoom);
    const char* name = velocity ? "Velocity" : "Position";
    return std::string("<tptz:") + name + ">" + inner + "</tptz:" + name + ">";
}

void read_vector(const XmlElement* v, PtzRequest& r)
{
    if (!v) return;
    if (const XmlElement* pt = v->child("PanTilt"))
        r.pan_tilt =
            PanTilt{parse_number(pt->attribute("x"), "PanTilt x"), parse_number(pt->attribute("y"), "PanTilt y")};
    if (const XmlElement* z = v->child("Zoom")) r.zoom = parse_number(z->attribute("x"), "Zoom x");
}

bool is_base64(std::string_view s)
{
    if (s.empty() || s.size() % 4 != 0) return false;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const char c = s[i];
        const bool pad = c == '=' && i + 2 >= s.size();
        if (!pad && !g_ascii_isalnum(c) && c != '+' && c != '/') return false;
    }
    return true;
}

}  // namespace

std::string printable(std::string_view text)
{
    std::string out;
    for (char c : text.substr(0, 160)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
    return text.size() > 160 ? out + "..." : out;
}

const XmlElement* XmlElement::child(std::string_view local) const
{
    for (const auto& c : children)
        if (c.name == local) return &c;
    return nullptr;
}

std::optional<std::string> XmlElement::attribute(std::string_view local) const
{
    for (const auto& [k, v] : attributes)
        if (k == local) return v;
    return std::nullopt;
}

Envelope parse_envelope(std::string_view xml)
{
    if (xml.size() > kMaxMessageBytes)
        throw SoapError("message longer than " + std::to_string(kMaxMessageBytes) + " bytes");
    static std::once_flag init;
    std::call_once(init, [] { xmlInitParser(); });
    const int options = XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_NOCDATA;
    std::unique_ptr<xmlDoc, DocFree> doc(
        xmlReadMemory(xml.data(), static_cast<int>(xml.size()), "message.xml", nullptr, options));
    if (!doc) throw SoapError("not well-formed XML");
    if (doc->intSubset || doc->extSubset) throw SoapError("document type declarations are not accepted");
    const xmlNode* root = xmlDocGetRootElement(doc.get());
    if (!root || std::string_view(local_name(root)) != "Envelope" || !root->ns ||
        std::string_view(reinterpret_cast<const char*>(root->ns->href)) != kSoapNs)
        throw SoapError("not a SOAP 1.2 envelope");
    XmlElement tree;
    int count = 0;
    convert(root, tree, 0, count);
    Envelope out;
    if (const XmlElement* h = tree.child("Header")) out.header = *h;
    const XmlElement& body = need(tree.child("Body"), "SOAP body");
    if (body.children.size() != 1) throw SoapError("the SOAP body does not hold one element");
    out.body = body.children.front();
    return out;
}

std::string password_digest(std::string_view nonce_base64, std::string_view created, std::string_view password)
{
    if (!is_base64(nonce_base64)) throw SoapError("the nonce is not Base64");
    const std::string nonce_text(nonce_base64);
    gsize nonce_len = 0;
    guchar* nonce = g_base64_decode(nonce_text.c_str(), &nonce_len);
    GChecksum* sha1 = g_checksum_new(G_CHECKSUM_SHA1);
    g_checksum_update(sha1, nonce, nonce_len);
    g_checksum_update(sha1, reinterpret_cast<const guchar*>(created.data()), created.size());
    g_checksum_update(sha1, reinterpret_cast<const guchar*>(password.data()), password.size());
    guint8 digest[20];
    gsize digest_len = sizeof digest;
    g_checksum_get_digest(sha1, digest, &digest_len);
    g_checksum_free(sha1);
    g_free(nonce);
    gchar* b64 = g_base64_encode(digest, digest_len);
    std::string out(b64);
    g_free(b64);
    return out;
}

UsernameToken make_username_token(const std::string& user, std::string_view password)
{
    guint8 raw[16];
    if (getrandom(raw, sizeof raw, 0) != static_cast<ssize_t>(sizeof raw))
        for (auto& b : raw) b = static_cast<guint8>(g_random_int());
    gchar* nonce = g_base64_encode(raw, sizeof raw);
    GDateTime* now = g_date_time_new_now_utc();
    gchar* created = g_date_time_format(now, "%Y-%m-%dT%H:%M:%SZ");
    UsernameToken t{user, {}, nonce, created};
    g_free(created);
    g_date_time_unref(now);
    g_free(nonce);
    t.digest = password_digest(t.nonce, t.created, password);
    return t;
}

std::optional<UsernameToken> username_token(const Envelope& envelope)
{
    const XmlElement* security = envelope.header.child("Security");
    const XmlElement* ut = security ? security->child("UsernameToken") : nullptr;
    if (!ut) return std::nullopt;
    const XmlElement& password = need(ut->child("Password"), "Password");
    if (password.attribute("Type").value_or("") != kDigestType) throw SoapError("only PasswordDigest is accepted");
    return UsernameToken{trimmed(need(ut->child("Username"), "Username").text), trimmed(password.text),
                         trimmed(need(ut->child("Nonce"), "Nonce").text),
                         trimmed(need(ut->child("Created"), "Created").text)};
}

std::string request_envelope(const PtzRequest& r, const std::optional<UsernameToken>& token)
{
    std::string body = "<tptz:" + r.operation + ">";
    body += element("ProfileToken", r.profile);
    if (r.operation == "AbsoluteMove") body += vector_element(r, false);
    if (r.operation == "ContinuousMove") body += vector_element(r, true);
    if (r.operation == "Stop") body += element("PanTilt", "true") + element("Zoom", "true");
    if ((r.operation == "SetPreset" && !r.preset_token.empty()) || r.operation == "GotoPreset")
        body += element("PresetToken", r.preset_token);
    body += "</tptz:" + r.operation + ">";
    return envelope_text(token ? security_header(*token) : std::string{}, body);
}

PtzRequest parse_request(const Envelope& envelope)
{
    PtzRequest r;
    r.operation = envelope.body.name;
    if (const XmlElement* p = envelope.body.child("ProfileToken")) r.profile = trimmed(p->text);
    read_vector(envelope.body.child(r.operation == "ContinuousMove" ? "Velocity" : "Position"), r);
    if (const XmlElement* p = envelope.body.child("PresetToken")) r.preset_token = trimmed(p->text);
    return r;
}

std::string status_response(const PtzStatus& s)
{
    const auto state = [](bool moving) { return moving ? "MOVING" : "IDLE"; };
    GDateTime* now = g_date_time_new_now_utc();
    gchar* utc = g_date_time_format(now, "%Y-%m-%dT%H:%M:%SZ");
    const std::string time(utc);
    g_free(utc);
    g_date_time_unref(now);
    return envelope_text({}, "<tptz:GetStatusResponse><tptz:PTZStatus><tt:Position>" +
                                 pan_tilt_element(s.pan_tilt, kPositionPanTilt) + zoom_element(s.zoom, kPositionZoom) +
                                 "</tt:Position><tt:MoveStatus><tt:PanTilt>" + state(s.pan_tilt_moving) +
                                 "</tt:PanTilt><tt:Zoom>" + state(s.zoom_moving) +
                                 "</tt:Zoom></tt:MoveStatus><tt:UtcTime>" + time +
                                 "</tt:UtcTime></tptz:PTZStatus></tptz:GetStatusResponse>");
}

std::string presets_response(const std::vector<Preset>& presets)
{
    std::string body = "<tptz:GetPresetsResponse>";
    for (const Preset& p : presets)
        body +=
            "<tptz:Preset token=\"" + escaped(p.token) + "\"><tt:Name>" + escaped(p.name) + "</tt:Name></tptz:Preset>";
    return envelope_text({}, body + "</tptz:GetPresetsResponse>");
}

std::string set_preset_response(const std::string& token)
{
    return envelope_text({}, "<tptz:SetPresetResponse>" + element("PresetToken", token) + "</tptz:SetPresetResponse>");
}

std::string empty_response(std::string_view operation)
{
    return envelope_text({}, "<tptz:" + std::string(operation) + "Response/>");
}

std::string fault_envelope(const Fault& f)
{
    return envelope_text({}, "<s:Fault><s:Code><s:Value>s:" + escaped(f.code) +
                                 "</s:Value><s:Subcode><s:Value>ter:" + escaped(f.subcode) +
                                 "</s:Value></s:Subcode></s:Code><s:Reason><s:Text xml:lang=\"en\">" +
                                 escaped(f.reason) + "</s:Text></s:Reason></s:Fault>");
}

std::optional<Fault> fault(const Envelope& envelope)
{
    if (envelope.body.name != "Fault") return std::nullopt;
    // Values are QNames ("s:Sender", "ter:NotAuthorized"): their local part is kept.
    const auto local = [](const std::string& qname) { return trimmed(qname.substr(qname.find(':') + 1)); };
    Fault f;
    if (const XmlElement* code = envelope.body.child("Code")) {
        if (const XmlElement* v = code->child("Value")) f.code = local(v->text);
        const XmlElement* sub = code->child("Subcode");
        if (const XmlElement* v = sub ? sub->child("Value") : nullptr) f.subcode = local(v->text);
    }
    const XmlElement* reason = envelope.body.child("Reason");
    if (const XmlElement* text = reason ? reason->child("Text") : nullptr) f.reason = trimmed(text->text);
    return f;
}

void expect_response(const Envelope& envelope, std::string_view operation)
{
    if (envelope.body.name != std::string(operation) + "Response")
        throw SoapError("expected " + std::string(operation) + "Response, got " + envelope.body.name.substr(0, 64));
}

PtzStatus parse_status(const Envelope& envelope)
{
    expect_response(envelope, "GetStatus");
    const XmlElement& status = need(envelope.body.child("PTZStatus"), "PTZStatus");
    const XmlElement& position = need(status.child("Position"), "Position");
    PtzStatus s;
    const XmlElement& pt = need(position.child("PanTilt"), "PanTilt position");
    s.pan_tilt = PanTilt{parse_number(pt.attribute("x"), "PanTilt x"), parse_number(pt.attribute("y"), "PanTilt y")};
    if (const XmlElement* z = position.child("Zoom")) s.zoom = parse_number(z->attribute("x"), "Zoom x");
    if (const XmlElement* move = status.child("MoveStatus")) {
        const XmlElement* pt_move = move->child("PanTilt");
        const XmlElement* zoom_move = move->child("Zoom");
        s.pan_tilt_moving = pt_move && trimmed(pt_move->text) == "MOVING";
        s.zoom_moving = zoom_move && trimmed(zoom_move->text) == "MOVING";
    }
    return s;
}

std::vector<Preset> parse_presets(const Envelope& envelope)
{
    expect_response(envelope, "GetPresets");
    std::vector<Preset> out;
    for (const XmlElement& p : envelope.body.children) {
        if (p.name != "Preset") continue;
        const XmlElement* name = p.child("Name");
        out.push_back(Preset{p.attribute("token").value_or(""), name ? trimmed(name->text) : std::string{}});
    }
    return out;
}

std::string parse_set_preset(const Envelope& envelope)
{
    expect_response(envelope, "SetPreset");
    return trimmed(need(envelope.body.child("PresetToken"), "PresetToken").text);
}

}  // namespace gc::headctl::onvif
