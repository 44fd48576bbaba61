// SPIR-V's physical layout (SPIR-V spec, 2.3 and 2.4): a 5-word header, then
// instructions whose first word is (word count << 16) | opcode.  OpDecorate
// (71) <target> SpecId (1) <id> names the constant; OpSpecConstant (50)
// <type> <result> <value> carries its default (one word for a 32-bit int).
#include "spec_constant.h"

#include <stdexcept>
#include <string>

namespace rrc_cache {
namespace {

constexpr uint32_t kMagic = 0x07230203u, kOpDecorate = 71, kOpSpecConstant = 50, kDecorationSpecId = 1;

// The word index of the default value of SpecId `id`'s OpSpecConstant in `m`.
size_t value_word(const std::vector<uint32_t>& m, uint32_t id) {
    if (m.size() < 5 || m[0] != kMagic) throw std::runtime_error("rrc-cache: not a SPIR-V module");
    uint32_t target = 0;
    bool named = false;
    for (size_t i = 5; i < m.size();) {
        const uint32_t count = m[i] >> 16, op = m[i] & 0xFFFFu;
        if (count == 0 || i + count > m.size()) throw std::runtime_error("rrc-cache: malformed SPIR-V module");
        if (op == kOpDecorate && count == 4 && m[i + 2] == kDecorationSpecId && m[i + 3] == id) target = m[i + 1], named = true;
        if (op == kOpSpecConstant && named && m[i + 2] == target) {
            if (count != 4) throw std::runtime_error("rrc-cache: specialization constant " + std::to_string(id) + " is not 32-bit");
            return i + 3;
        }
        i += count;
    }
    throw std::runtime_error("rrc-cache: the module has no integer specialization constant " + std::to_string(id));
}

}  // namespace

std::vector<uint32_t> with_spec_constant(const uint32_t* words, size_t bytes, uint32_t id, uint32_t value) {
    std::vector<uint32_t> m(words, words + bytes / sizeof(uint32_t));
    m[value_word(m, id)] = value;
    return m;
}

uint32_t spec_constant(const std::vector<uint32_t>& module, uint32_t id) { return module[value_word(module, id)]; }

}  // namespace rrc_cache
