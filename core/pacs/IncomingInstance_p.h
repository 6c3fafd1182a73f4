#pragma once
// An instance that arrived over DICOM (C-GET sub-operation, C-MOVE or a push):
// written whole under the store's tmp/ and moved in. Private to lucent_pacs.

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdatset.h>

#include "core/store/StudyStore.h"

namespace lucent {

// True when added, false when the store already had it. Throws StoreError.
bool storeIncoming(DcmDataset& dataset, StudyStore& store);

} // namespace lucent
