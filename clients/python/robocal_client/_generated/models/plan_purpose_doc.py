from enum import StrEnum

class PlanPurposeDoc(StrEnum):
    CALIBRATION = "calibration"
    QUICK_CHECK = "quick_check"

    def __str__(self) -> str:
        return str(self.value)
