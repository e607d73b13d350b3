// The command catalogue against the code that runs the commands: every protocol that plans a
// command accepts the catalogue's example, accepts each parameter at the ends of its range,
// refuses it beyond them, refuses a wrong type, needs the required ones and knows every one
// the catalogue lists - so the docs and gimbalctl's help, generated from the catalogue, say
// what the daemon does. Also the roles and envelope flags derived from it.
#include <catch2/catch.hpp>
#include <set>

#include "../vehicle/vehicle_fixtures.hpp"
#include "auth/roles.hpp"
#include "command/catalogue.hpp"
#include "command/envelope.hpp"
#include "protocols/registry.hpp"

using namespace gimbal;
using command::ParamType;
using nlohmann::json;

namespace {

struct Planned {
    std::optional<command::Error> error;
};

// The vehicle feed has told the session where the aircraft is (a protocol that aims its
// gimbal from the vehicle's state needs it for geopoint and path).
Planned plan(const protocols::Entry& e, std::string_view cmd, const json& request) {
    const json gimbal = {{"name", "g"}, {"protocol", e.name}};
    auto session = e.make_session(protocols::SessionSettings{}, gimbal);
    vehicle::VehicleState v(vehicle_fixtures::options());
    vehicle_fixtures::fix_at(v, 1.0);
    std::vector<session::Bytes> steering;
    session->steer(v, 1.0, 1.0, steering);
    command::Plan p;
    return {session->plan(cmd, request, {1.0, 1'790'000'000.0}, p)};
}

std::string describe(const Planned& p) {
    return p.error ? std::string(to_string(p.error->code)) + ": " + p.error->message : "ok";
}

// The message names the key: 'key' (the planners) or "key: ..." (a packet's JSON reader).
bool mentions(const Planned& p, std::string_view key) {
    if (!p.error) return false;
    const std::string& m = p.error->message;
    return m.find("'" + std::string(key) + "'") != std::string::npos ||
           m.rfind(std::string(key) + ":", 0) == 0;
}

// A value of the parameter's type that is valid on its own.
json valid_value(const command::ParamSpec& p) {
    switch (p.type) {
        case ParamType::number:
        case ParamType::integer:
            return p.min;
        case ParamType::boolean:
            return false;
        case ParamType::text:
            return "";
        case ParamType::choice:
            return std::string(p.choices.front());
        case ParamType::numbers:
            return json(std::vector<double>(p.count, p.min));
        case ParamType::points:
            return json::array({{{"lat", 1.0}, {"lon", 2.0}, {"alt", 3.0}}});
        case ParamType::keys:
            return json::array();
    }
    return nullptr;
}

}  // namespace

TEST_CASE("catalogue: names are unique, parameters well formed") {
    std::set<std::string_view> names;
    for (const auto& c : command::catalogue()) {
        INFO(c.name);
        CHECK(names.insert(c.name).second);
        CHECK_FALSE(c.summary.empty());
        CHECK(command::find_command(c.name) == &c);
        CHECK(command::is_known_command(c.name));
        const json example = json::parse(c.example, nullptr, false);
        CHECK(example.is_object());
        std::set<std::string_view> params;
        for (const auto& p : c.params) {
            INFO(p.name);
            CHECK(params.insert(p.name).second);
            CHECK(command::find_param(c, p.name) == &p);
            if (p.type == ParamType::choice) CHECK_FALSE(p.choices.empty());
            if (p.type == ParamType::numbers) CHECK(p.count > 0);
            if (p.type == ParamType::number || p.type == ParamType::integer) CHECK(p.min <= p.max);
            CHECK_FALSE((p.required && !p.default_text.empty()));
        }
        for (const auto& [key, value] : example.items()) CHECK(command::find_param(c, key));
        if (c.scope != command::Scope::protocol) CHECK_FALSE(c.reply.empty());
    }
    CHECK_FALSE(command::is_known_command("fly"));
}

TEST_CASE("catalogue: every planner agrees with each parameter's schema") {
    for (const auto& c : command::catalogue()) {
        for (const auto* e : protocols::planners_of(c.name)) {
            INFO(e->name << " " << c.name);
            const json example = json::parse(c.example);
            {
                const auto p = plan(*e, c.name, example);
                INFO(describe(p));
                CHECK_FALSE(p.error);
            }
            {
                json r = example;
                r["bogus"] = 1;
                const auto p = plan(*e, c.name, r);
                INFO(describe(p));
                CHECK(p.error);
            }
            for (const auto& param : c.params) {
                INFO("parameter " << param.name);
                const std::string key(param.name);
                // Known: a valid value is never an unknown parameter.
                json r = example;
                r[key] = valid_value(param);
                const auto known = plan(*e, c.name, r);
                INFO(describe(known));
                CHECK_FALSE((known.error &&
                             known.error->message.find("unknown parameter") != std::string::npos));
                if (param.required) {
                    json missing = example;
                    missing.erase(key);
                    const auto p = plan(*e, c.name, missing);
                    INFO(describe(p));
                    CHECK(p.error);
                    CHECK(mentions(p, key));
                }
                if (param.type == ParamType::number || param.type == ParamType::integer) {
                    for (const double v : {param.min, param.max}) {
                        json ok = example;
                        ok[key] = v;
                        const auto p = plan(*e, c.name, ok);
                        INFO(v << " -> " << describe(p));
                        CHECK_FALSE(mentions(p, key));
                    }
                    for (const double v : {param.min - 1, param.max + 1}) {
                        json bad = example;
                        bad[key] = v;
                        const auto p = plan(*e, c.name, bad);
                        INFO(v << " -> " << describe(p));
                        REQUIRE(p.error);
                        CHECK(mentions(p, key));
                        CHECK(p.error->code == command::ErrorCode::out_of_range);
                    }
                }
                if (param.type == ParamType::integer) {
                    json bad = example;
                    bad[key] = param.min + 0.5;
                    const auto p = plan(*e, c.name, bad);
                    INFO(describe(p));
                    CHECK(mentions(p, key));
                }
                if (param.type == ParamType::numbers) {
                    json bad = example;
                    bad[key] = std::vector<double>(param.count, param.max + 1);
                    CHECK(mentions(plan(*e, c.name, bad), key));
                    bad[key] = std::vector<double>(param.count + 1, param.min);
                    CHECK(mentions(plan(*e, c.name, bad), key));
                }
                if (param.type == ParamType::text) {
                    json bad = example;
                    bad[key] = std::string(static_cast<std::size_t>(param.max) + 1, 'a');
                    CHECK(mentions(plan(*e, c.name, bad), key));
                }
                if (param.type == ParamType::choice) {
                    json bad = example;
                    bad[key] = "no-such-choice";
                    CHECK(mentions(plan(*e, c.name, bad), key));
                }
                // A wrong type is refused, naming the key.
                json wrong = example;
                wrong[key] = param.type == ParamType::boolean ? json("yes") : json(true);
                const auto p = plan(*e, c.name, wrong);
                INFO("wrong type -> " << describe(p));
                CHECK(mentions(p, key));
            }
        }
    }
}

TEST_CASE("roles come from the catalogue, with the laser's fire rule") {
    using auth::Role;
    const json none = json::object();
    CHECK_FALSE(auth::required_role("ping", none));
    CHECK_FALSE(auth::required_role("version", none));
    CHECK_FALSE(auth::required_role("list", none));
    CHECK(auth::required_role("state", none) == Role::observe);
    CHECK(auth::required_role("subscribe", none) == Role::observe);
    CHECK(auth::required_role("unsubscribe", none) == Role::observe);
    CHECK(auth::required_role("position", none) == Role::control);
    CHECK(auth::required_role("viewpro_adjust", none) == Role::control);
    CHECK(auth::required_role("laser", json{{"fire", false}}) == Role::control);
    CHECK(auth::required_role("laser", json{{"fire", true}}) == Role::laser);
    CHECK(auth::required_role("laser", none) == Role::laser);
    CHECK(auth::required_role("laser", json{{"fire", "no"}}) == Role::laser);
    CHECK(auth::required_role("no_such_command", none) == Role::control);
}

TEST_CASE("envelope flags are views of the catalogue") {
    for (const char* c : {"ping", "version", "list"}) {
        CHECK(command::is_common_command(c));
        CHECK(command::is_open_command(c));
        CHECK(command::is_global_command(c));
    }
    CHECK(command::is_common_command("state"));
    CHECK(command::is_open_command("state"));
    CHECK_FALSE(command::is_global_command("state"));
    for (const char* c : {"subscribe", "unsubscribe"}) {
        CHECK(command::is_common_command(c));
        CHECK_FALSE(command::is_open_command(c));
        CHECK_FALSE(command::is_global_command(c));
    }
    for (const char* c : {"geopoint", "laser", "viewpro_output", "fly"}) {
        CHECK_FALSE(command::is_common_command(c));
        CHECK_FALSE(command::is_open_command(c));
        CHECK_FALSE(command::is_global_command(c));
    }
}
