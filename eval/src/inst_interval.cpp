// Explicit instantiation of the generic pipeline for one scalar type.
#include <qverify/eval/instantiate.hpp>
QVERIFY_INSTANTIATE(::qverify::Interval)
