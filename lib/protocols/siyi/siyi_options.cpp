#include "protocols/siyi/siyi_options.hpp"

namespace gimbal::protocols {

SiyiOptions read_siyi_options(const nlohmann::json& gimbal) {
    SiyiOptions o;
    static_cast<SiyiConfig&>(o) = config::read_checked<SiyiConfig>(gimbal);
    return o;
}

std::optional<siyi::Model> configured_model(SiyiModelSetting setting) {
    switch (setting) {
        case SiyiModelSetting::detect:
            return std::nullopt;
        case SiyiModelSetting::a8mini:
            return siyi::Model::a8_mini;
        case SiyiModelSetting::zr10:
            return siyi::Model::zr10;
        case SiyiModelSetting::zr30:
            return siyi::Model::zr30;
        case SiyiModelSetting::zt30:
            return siyi::Model::zt30;
        case SiyiModelSetting::zt6:
            return siyi::Model::zt6;
    }
    return std::nullopt;
}

}  // namespace gimbal::protocols
