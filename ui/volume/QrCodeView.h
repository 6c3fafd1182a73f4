#pragma once
// A QR code (remote::QrCode, made by the server with libqrencode) drawn dark on
// white with its quiet zone, as large as the widget allows in whole pixels a
// module, so that a phone across a lecture hall reads it.

#include <QWidget>

#include "protocol/QrCode.h"

namespace lucent {

class QrCodeView : public QWidget {
    Q_OBJECT
public:
    explicit QrCodeView(QWidget* parent = nullptr);
    void setCode(const remote::QrCode& code); // an empty code draws nothing
    const remote::QrCode& code() const { return code_; }
    // The code as an image: `scale` pixels a module, the quiet zone included.
    QImage image(int scale) const;
    QSize sizeHint() const override;

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    remote::QrCode code_;
};

} // namespace lucent
