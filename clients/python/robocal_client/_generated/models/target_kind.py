from enum import StrEnum

class TargetKind(StrEnum):
    ASYMMETRIC_CIRCLES = "asymmetric_circles"
    CHARUCO = "charuco"
    CHESSBOARD = "chessboard"
    DOTS = "dots"

    def __str__(self) -> str:
        return str(self.value)
