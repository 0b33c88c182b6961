from enum import StrEnum

class JobKind(StrEnum):
    CALIBRATION = "calibration"
    CHECK = "check"

    def __str__(self) -> str:
        return str(self.value)
