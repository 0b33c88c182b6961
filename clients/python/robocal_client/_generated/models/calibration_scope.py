from enum import StrEnum

class CalibrationScope(StrEnum):
    BASE = "base"
    FULL = "full"
    HAND_EYE = "hand_eye"

    def __str__(self) -> str:
        return str(self.value)
