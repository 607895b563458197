// Closes the diagnostic scope util/ThirdPartyBegin.hpp opened.
// No include guard: it pairs with each use of ThirdPartyBegin.hpp.
#pragma GCC diagnostic pop
